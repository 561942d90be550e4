// Internal entry points of the per-format mesh readers and writers (dispatch in mesh_io.cpp).
#pragma once

#include "mesh_io.hpp"

#include <string>
#include <string_view>

namespace pathlet::io {

Mesh read_stl(std::string_view bytes, bool binary, const std::string& file, LoadReport& report);
std::string write_stl_binary(const Mesh& mesh);
Mesh read_obj(std::string_view bytes, const std::string& file, LoadReport& report);
std::string write_obj(const Mesh& mesh);
Mesh read_gltf(std::string_view bytes, bool binary, const std::string& file, LoadReport& report);
std::string write_gltf(const Mesh& mesh, bool binary, const std::string& file);

// Checks indices < vertices, drops degenerate (repeated-index) and non-finite triangles
// with a warning, computes normals when absent. Shared by all mesh readers.
void finish_mesh(Mesh& mesh, LoadReport& report, const std::string& file);

}  // namespace pathlet::io
