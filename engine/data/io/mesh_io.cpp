// Mesh load/save dispatch plus the shared mesh validation step.
#include "mesh_io.hpp"

#include "byte_reader.hpp"
#include "file_bytes.hpp"
#include "mesh_formats.hpp"
#include "util/atomic_file.hpp"

#include <cmath>

namespace pathlet::io {

void finish_mesh(Mesh& m, LoadReport& report, const std::string& file) {
    const size_t n = m.position.size();
    if (m.index.size() % 3) fail_at(file, "mesh", std::to_string(m.index.size()) + " indices is not a multiple of 3");
    for (size_t i = 0; i < m.index.size(); ++i)
        if (m.index[i] >= n)
            fail_at(file, "mesh", "triangle " + std::to_string(i / 3) + " uses vertex " + std::to_string(m.index[i]) +
                                      " but there are only " + std::to_string(n) + " vertices");
    auto finite = [](const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
    size_t degenerate = 0, nonfinite = 0, w = 0;
    for (size_t t = 0; t + 2 < m.index.size(); t += 3) {
        uint32_t a = m.index[t], b = m.index[t + 1], c = m.index[t + 2];
        if (a == b || b == c || a == c) { ++degenerate; continue; }
        if (!finite(m.position[a]) || !finite(m.position[b]) || !finite(m.position[c])) { ++nonfinite; continue; }
        m.index[w++] = a;
        m.index[w++] = b;
        m.index[w++] = c;
    }
    m.index.resize(w);
    if (degenerate) report.warnings.push_back("dropped " + std::to_string(degenerate) + " degenerate triangles (repeated vertex)");
    if (nonfinite) report.warnings.push_back("dropped " + std::to_string(nonfinite) + " triangles with NaN/inf vertices");
    if (m.index.empty()) report.warnings.push_back("the mesh has no triangles");
    if (m.normal.size() != n) m.compute_normals();
}

Mesh load_mesh(const std::string& path, LoadReport* report) {
    LoadReport local;
    LoadReport& r = report ? *report : local;
    std::string bytes = read_file_bytes(path);
    switch (Sniffed s = sniff(bytes, path)) {
        case Sniffed::StlBinary: return read_stl(bytes, true, path, r);
        case Sniffed::StlAscii: return read_stl(bytes, false, path, r);
        case Sniffed::Obj: return read_obj(bytes, path, r);
        case Sniffed::Gltf: return read_gltf(bytes, false, path, r);
        case Sniffed::Glb: return read_gltf(bytes, true, path, r);
        default:
            fail_at(path, at_byte(0), std::string("not a supported mesh (") + sniffed_name(s) +
                                          "); meshes are glTF 2.0 (.gltf/.glb), STL or OBJ");
    }
}

void save_mesh(const Mesh& mesh, const std::string& path) {
    for (auto i : mesh.index)  // validate before writing anything
        if (i >= mesh.position.size()) fail_at(path, "mesh", "index " + std::to_string(i) + " out of range");
    if (mesh.index.size() % 3) fail_at(path, "mesh", "index count is not a multiple of 3");
    std::string ext = lower_extension(path), bytes;
    if (ext == ".stl") bytes = write_stl_binary(mesh);
    else if (ext == ".obj") bytes = write_obj(mesh);
    else if (ext == ".gltf" || ext == ".glb") bytes = write_gltf(mesh, ext == ".glb", path);
    else fail_at(path, at_byte(0), "cannot choose a mesh format from extension '" + ext + "' (use .gltf, .glb, .stl or .obj)");
    try {
        write_file_atomic(path, bytes);
    } catch (const std::runtime_error& e) {
        throw DataError(e.what());
    }
}

}  // namespace pathlet::io
