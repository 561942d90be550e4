#include "io_test_util.hpp"

#include "io/native_cache.hpp"
#include "io/pathline_formats.hpp"

#include <cmath>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace fs = std::filesystem;

namespace iotest {

pathlet::Pathlines make_lines(size_t lines, size_t per_line, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    pathlet::Pathlines p;
    for (size_t l = 0; l < lines; ++l) {
        size_t n = per_line + (l % 5);
        uint32_t first = uint32_t(p.position.size());
        glm::vec3 x{u(rng) * 10.0f, u(rng) * 10.0f, u(rng) * 10.0f};
        float t = 0.013f * float(l % 7) + 0.0001f * u(rng) + 0.001f;
        for (size_t k = 0; k < n; ++k) {
            glm::vec3 v{std::sin(0.3f * float(k) + float(l)) + 1.7f, std::cos(0.2f * float(k)) * 0.9f + u(rng) * 0.1f,
                        0.5f + 0.1f * u(rng)};
            p.position.push_back(x);
            p.time.push_back(t);
            p.velocity.push_back(v);
            float dt = 0.01f + 0.001f * (u(rng) + 1.0f);
            x += v * dt;
            t += dt;
        }
        p.lines.push_back({first, uint32_t(n)});
    }
    return p;
}

std::string temp_dir() {
    auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path d = fs::path(PATHLET_TEST_BINARY_DIR) / "io-tmp" / (std::string(info->test_suite_name()) + "." + info->name());
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

std::string read_bytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

void write_bytes(const std::string& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
}

static bool same_bits(float a, float b) { return std::memcmp(&a, &b, 4) == 0; }

void expect_same(const pathlet::Pathlines& a, const pathlet::Pathlines& b) {
    ASSERT_EQ(a.position.size(), b.position.size());
    ASSERT_EQ(a.time.size(), b.time.size());
    ASSERT_EQ(a.velocity.size(), b.velocity.size());
    ASSERT_EQ(a.lines.size(), b.lines.size());
    for (size_t i = 0; i < a.lines.size(); ++i) {
        ASSERT_EQ(a.lines[i].first, b.lines[i].first) << "line " << i;
        ASSERT_EQ(a.lines[i].count, b.lines[i].count) << "line " << i;
    }
    for (size_t i = 0; i < a.position.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(same_bits(a.position[i][k], b.position[i][k])) << "position " << i << " " << a.position[i][k] << " vs " << b.position[i][k];
            ASSERT_TRUE(same_bits(a.velocity[i][k], b.velocity[i][k])) << "velocity " << i;
        }
        ASSERT_TRUE(same_bits(a.time[i], b.time[i])) << "time " << i;
    }
}

std::string real_data_dir() {
    const char* env = std::getenv("PATHLET_REAL_DATA_DIR");
    std::string d = env && *env ? env : std::string(PATHLET_SOURCE_DIR) + "/../shared/data/real";
    return fs::is_directory(d) ? d : "";
}

bool reports(const pathlet::io::LoadReport& r, const std::string& needle) {
    for (const auto* list : {&r.warnings, &r.arrays})
        for (const auto& w : *list)
            if (w.find(needle) != std::string::npos) return true;
    return false;
}

std::vector<std::pair<std::string, std::string>> every_writer(const pathlet::Pathlines& p) {
    using namespace pathlet::io;
    std::vector<std::pair<std::string, std::string>> files = {
        {"a.vtk", write_vtk_legacy(p, {false, false})}, {"b.vtk", write_vtk_legacy(p, {true, false})},
        {"c.vtk", write_vtk_legacy(p, {true, true})}, {"n.pathlet", encode_native(p)}};
    using E = VtpWriteOptions::Encoding;
    for (E e : {E::Ascii, E::Inline, E::AppendedRaw, E::AppendedBase64})
        for (bool z : {false, true}) {
            VtpWriteOptions o;
            o.encoding = e;
            o.zlib = z && e != E::Ascii;
            files.push_back({"v" + std::to_string(int(e)) + std::to_string(z) + ".vtp", write_vtp(p, o)});
        }
    return files;
}

}  // namespace iotest
