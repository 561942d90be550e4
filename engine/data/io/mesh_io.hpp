// Triangle mesh import/export (vessel walls): glTF 2.0 (.gltf/.glb via tinygltf),
// STL (ascii + binary; identical vertices merged on load) and OBJ (v, vn, f; polygons
// fan-triangulated, negative indices). Errors throw pathlet::DataError.
#pragma once

#include "pathline_io.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet::io {

Mesh load_mesh(const std::string& path, LoadReport* report = nullptr);
// By extension: .gltf/.glb (tinygltf), .stl (binary), .obj.
void save_mesh(const Mesh& mesh, const std::string& path);

}  // namespace pathlet::io
