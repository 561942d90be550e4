// STL reader (ascii and binary) and binary writer. STL stores three separate corners per
// facet; identical corners are merged so the mesh is indexed and normals are smooth.
#include "byte_reader.hpp"
#include "mesh_formats.hpp"

#include <cstring>
#include <unordered_map>

namespace pathlet::io {

namespace {

struct VecHash {
    size_t operator()(const glm::vec3& v) const {
        uint32_t a[3];
        std::memcpy(a, &v, 12);
        return (size_t(a[0]) * 73856093u) ^ (size_t(a[1]) * 19349663u) ^ (size_t(a[2]) * 83492791u);
    }
};

struct Merger {
    Mesh& m;
    std::unordered_map<glm::vec3, uint32_t, VecHash> seen;
    void add(const glm::vec3& p) {
        glm::vec3 key = p + glm::vec3(0.0f);  // -0 and +0 merge
        auto [it, fresh] = seen.try_emplace(key, uint32_t(m.position.size()));
        if (fresh) m.position.push_back(p);
        m.index.push_back(it->second);
    }
};

}  // namespace

Mesh read_stl(std::string_view b, bool binary, const std::string& file, LoadReport& report) {
    Mesh m;
    Merger merge{m, {}};
    if (binary) {
        report.format = "STL binary";
        if (b.size() < 84) fail_at(file, at_byte(b.size()), "binary STL is shorter than its 84-byte header (truncated)");
        uint32_t n;
        std::memcpy(&n, b.data() + 80, 4);
        if (uint64_t(n) * 50 != b.size() - 84)
            fail_at(file, at_byte(80), "binary STL declares " + std::to_string(n) + " triangles (" + std::to_string(84 + uint64_t(n) * 50) +
                                           " bytes) but the file has " + std::to_string(b.size()) + " bytes (truncated or corrupt)");
        m.index.reserve(size_t(n) * 3);
        merge.seen.reserve(size_t(n));
        for (uint32_t t = 0; t < n; ++t) {
            const char* f = b.data() + 84 + size_t(t) * 50 + 12;  // skip the facet normal
            for (int k = 0; k < 3; ++k) {
                glm::vec3 p;
                std::memcpy(&p, f + 12 * k, 12);
                merge.add(p);
            }
        }
    } else {
        report.format = "STL ascii";
        Cursor c(b, file);
        c.expect_token("solid");
        c.rest_of_line();
        while (true) {
            auto t = c.token();
            if (t.empty() || iequals(t, "endsolid")) break;
            if (iequals(t, "vertex")) {
                glm::vec3 p;
                for (int k = 0; k < 3; ++k) {
                    auto v = c.expect_token("vertex coordinate");
                    if (!parse_number(v, p[k])) c.fail("vertex coordinate '" + std::string(v) + "' is not a number");
                }
                merge.add(p);
            } else if (iequals(t, "facet") || iequals(t, "normal") || iequals(t, "outer") || iequals(t, "loop") ||
                       iequals(t, "endloop") || iequals(t, "endfacet")) {
                if (iequals(t, "normal")) for (int k = 0; k < 3; ++k) c.expect_token("normal component");
            } else {
                c.fail("unexpected '" + std::string(t.substr(0, 40)) + "' in ascii STL");
            }
        }
        if (m.index.size() % 3 != 0)
            c.fail("ascii STL has " + std::to_string(m.index.size()) + " vertices, not a multiple of 3 (truncated facet?)");
    }
    report.warnings.push_back("merged identical STL corners: " + std::to_string(m.index.size()) + " corners -> " +
                              std::to_string(m.position.size()) + " vertices");
    finish_mesh(m, report, file);
    return m;
}

std::string write_stl_binary(const Mesh& m) {
    const size_t n = m.index.size() / 3;
    std::string s(84 + n * 50, '\0');
    std::memcpy(s.data(), "pathlet binary STL", 18);
    uint32_t n32 = uint32_t(n);
    std::memcpy(s.data() + 80, &n32, 4);
    for (size_t t = 0; t < n; ++t) {
        char* f = s.data() + 84 + t * 50;
        glm::vec3 a = m.position[m.index[3 * t]], b = m.position[m.index[3 * t + 1]], c = m.position[m.index[3 * t + 2]];
        glm::vec3 nrm = glm::cross(b - a, c - a);
        float l = glm::length(nrm);
        nrm = l > 0 ? nrm / l : glm::vec3(0.0f);
        std::memcpy(f, &nrm, 12);
        std::memcpy(f + 12, &a, 12);
        std::memcpy(f + 24, &b, 12);
        std::memcpy(f + 36, &c, 12);
    }
    return s;
}

}  // namespace pathlet::io
