// Wavefront OBJ: v, vn and f (v, v/vt, v//vn, v/vt/vn; negative = relative to the end);
// polygons are fan-triangulated. Other statements (vt, o, g, s, usemtl...) are ignored.
#include "byte_reader.hpp"
#include "mesh_formats.hpp"

#include <cstdio>
#include <map>

namespace pathlet::io {

Mesh read_obj(std::string_view bytes, const std::string& file, LoadReport& report) {
    report.format = "Wavefront OBJ";
    std::vector<glm::vec3> v, vn;
    struct Corner { int64_t v, n; };
    std::vector<Corner> corners;  // 3 per triangle
    std::vector<Corner> poly;
    Cursor c(bytes, file);
    size_t polygons = 0;
    while (!c.at_end()) {
        size_t line_no = c.line();
        auto line = c.rest_of_line();
        Cursor lc(line, file);
        auto fail = [&](const std::string& m) { fail_at(file, at_line(line_no), m); };
        auto kw = lc.token();
        if (kw == "v" || kw == "vn") {
            glm::vec3 p;
            for (int k = 0; k < 3; ++k) {
                auto t = lc.token();
                if (!parse_number(t, p[k])) fail("'" + std::string(kw) + "' needs 3 numbers, got '" + std::string(t) + "'");
            }
            (kw == "v" ? v : vn).push_back(p);
        } else if (kw == "f") {
            poly.clear();
            for (auto t = lc.token(); !t.empty(); t = lc.token()) {
                Corner cr{0, -1};
                auto s1 = t.find('/');
                if (!parse_number(t.substr(0, s1), cr.v)) fail("bad face vertex '" + std::string(t) + "'");
                if (s1 != std::string_view::npos) {
                    auto s2 = t.find('/', s1 + 1);
                    if (s2 != std::string_view::npos && s2 + 1 < t.size()) {
                        if (!parse_number(t.substr(s2 + 1), cr.n)) fail("bad face normal index in '" + std::string(t) + "'");
                        cr.n = cr.n < 0 ? int64_t(vn.size()) + cr.n : cr.n - 1;
                        if (cr.n < 0 || cr.n >= int64_t(vn.size()))
                            fail("face normal index in '" + std::string(t) + "' refers to a normal not defined yet (" +
                                 std::to_string(vn.size()) + " so far)");
                    }
                }
                cr.v = cr.v < 0 ? int64_t(v.size()) + cr.v : cr.v - 1;
                if (cr.v < 0 || cr.v >= int64_t(v.size()))
                    fail("face index in '" + std::string(t) + "' refers to a vertex not defined yet (" + std::to_string(v.size()) + " so far)");
                poly.push_back(cr);
            }
            if (poly.size() < 3) fail("face with " + std::to_string(poly.size()) + " vertices (need at least 3)");
            if (poly.size() > 3) ++polygons;
            for (size_t k = 1; k + 1 < poly.size(); ++k) corners.insert(corners.end(), {poly[0], poly[k], poly[k + 1]});
        }
    }
    if (polygons) report.warnings.push_back("triangulated " + std::to_string(polygons) + " polygons with more than 3 corners");
    Mesh m;
    // Keep the file's vertex order when each corner's normal index matches its vertex index
    // (or there are none); otherwise every distinct (vertex, normal) pair becomes a vertex.
    bool identity = true, all_normals = !corners.empty();
    for (auto& cr : corners) {
        if (cr.n >= 0 && cr.n != cr.v) identity = false;
        if (cr.n < 0) all_normals = false;
    }
    if (identity) {
        m.position = std::move(v);
        for (auto& cr : corners) m.index.push_back(uint32_t(cr.v));
        if (all_normals && vn.size() >= m.position.size()) m.normal.assign(vn.begin(), vn.begin() + m.position.size());
    } else {
        std::map<std::pair<int64_t, int64_t>, uint32_t> ids;
        for (auto& cr : corners) {
            auto [it, fresh] = ids.try_emplace({cr.v, cr.n}, uint32_t(m.position.size()));
            if (fresh) {
                m.position.push_back(v[size_t(cr.v)]);
                m.normal.push_back(cr.n >= 0 ? vn[size_t(cr.n)] : glm::vec3(0.0f));
            }
            m.index.push_back(it->second);
        }
        if (!all_normals) m.normal.clear();
    }
    finish_mesh(m, report, file);
    return m;
}

std::string write_obj(const Mesh& m) {
    std::string s = "# pathlet mesh\n";
    char buf[128];
    for (auto& p : m.position) s.append(buf, size_t(std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p.x, p.y, p.z)));
    for (auto& n : m.normal) s.append(buf, size_t(std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z)));
    const bool normals = m.normal.size() == m.position.size() && !m.normal.empty();
    for (size_t i = 0; i + 2 < m.index.size(); i += 3) {
        unsigned a = m.index[i] + 1, b = m.index[i + 1] + 1, c = m.index[i + 2] + 1;
        int k = normals ? std::snprintf(buf, sizeof buf, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c)
                        : std::snprintf(buf, sizeof buf, "f %u %u %u\n", a, b, c);
        s.append(buf, size_t(k));
    }
    return s;
}

}  // namespace pathlet::io
