// Mesh round trips (STL binary, OBJ, glTF, GLB) and mesh-specific parsing rules.
#include "io/mesh_io.hpp"
#include "io_test_util.hpp"

#include <cmath>
#include <filesystem>
#include <cstring>
#include <algorithm>
#include <array>
#include <set>

#include <glm/glm.hpp>

using namespace pathlet;
using namespace pathlet::io;

namespace {

// A closed, irregular octahedron-like mesh with non-round coordinates.
Mesh make_mesh() {
    Mesh m;
    m.position = {{0.1f, 0.2f, 1.3f}, {1.17f, 0.0f, 0.01f}, {0.0f, 1.2345678f, -0.1f},
                  {-1.0f, 0.3f, 0.0f}, {0.0f, -1.1f, 0.2f}, {0.05f, 0.0f, -1.3333333f}};
    m.index = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 5, 2, 1, 5, 3, 2, 5, 4, 3, 5, 1, 4};
    m.compute_normals();
    return m;
}

bool same(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, 12) == 0; }

TEST(IoMesh, RoundTripEveryFormat) {
    Mesh m = make_mesh();
    std::string dir = iotest::temp_dir();
    for (const char* ext : {".stl", ".obj", ".gltf", ".glb"}) {
        SCOPED_TRACE(ext);
        std::string path = dir + "/m" + ext;
        save_mesh(m, path);
        LoadReport r;
        Mesh q = load_mesh(path, &r);
        ASSERT_EQ(q.position.size(), m.position.size());
        ASSERT_EQ(q.index, m.index);  // STL merge keeps first-use order, which matches here
        for (size_t i = 0; i < m.position.size(); ++i) EXPECT_TRUE(same(q.position[i], m.position[i])) << i;
        ASSERT_EQ(q.normal.size(), m.normal.size());
        if (std::string(ext) != ".stl") {  // STL has facet normals only; recomputed ones match
            for (size_t i = 0; i < m.normal.size(); ++i) EXPECT_TRUE(same(q.normal[i], m.normal[i])) << i;
        }
    }
}

TEST(IoMesh, StlAsciiAndMerging) {
    std::string s = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                    "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
    std::string path = iotest::temp_dir() + "/a.stl";
    iotest::write_bytes(path, s);
    LoadReport r;
    Mesh m = load_mesh(path, &r);
    EXPECT_EQ(r.format, "STL ascii");
    EXPECT_EQ(m.position.size(), 4u);
    EXPECT_EQ(m.index, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_NEAR(m.normal[0].z, 1.0f, 1e-6f);
}

TEST(IoMesh, BinaryStlStartingWithSolidIsBinary) {
    Mesh m = make_mesh();
    std::string dir = iotest::temp_dir();
    save_mesh(m, dir + "/a.stl");
    std::string b = iotest::read_bytes(dir + "/a.stl");
    std::memcpy(b.data(), "solid facet header", 18);
    iotest::write_bytes(dir + "/b.stl", b);
    LoadReport r;
    EXPECT_EQ(load_mesh(dir + "/b.stl", &r).index.size(), m.index.size());
    EXPECT_EQ(r.format, "STL binary");
    iotest::write_bytes(dir + "/c.stl", b.substr(0, b.size() - 7));  // truncated: size rule fails
    EXPECT_THROW(load_mesh(dir + "/c.stl"), DataError);
}

TEST(IoMesh, ObjPolygonsNegativeIndicesAndNormals) {
    std::string s = "# quad + pentagon\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\n"
                    "f 1/1/1 2/1/1 3/1/1 4/1/1\nv 2 0 0\nv 2 1 0\nf -1 -2 2 3\n";
    std::string path = iotest::temp_dir() + "/a.obj";
    iotest::write_bytes(path, s);
    LoadReport r;
    Mesh m = load_mesh(path, &r);
    EXPECT_EQ(m.index.size(), 12u);  // 2 + 2 triangles
    EXPECT_FALSE(r.warnings.empty());
    iotest::write_bytes(path, "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    try {
        load_mesh(path);
        FAIL();
    } catch (const DataError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": line 3: ", 0), 0u) << e.what();
    }
}

TEST(IoMesh, GltfGarbageAndPathlinesRejected) {
    std::string dir = iotest::temp_dir();
    iotest::write_bytes(dir + "/a.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {");
    EXPECT_THROW(load_mesh(dir + "/a.gltf"), DataError);
    iotest::write_bytes(dir + "/b.glb", "glTF\x02\0\0\0");
    EXPECT_THROW(load_mesh(dir + "/b.glb"), DataError);
    iotest::write_bytes(dir + "/rows", "0 0 0 1 1 1\n");
    EXPECT_THROW(load_mesh(dir + "/rows"), DataError);
    EXPECT_THROW(save_mesh(make_mesh(), dir + "/m.ply"), DataError);
}

}  // namespace

TEST(MeshIo, GltfExternalFilesStayInsideTheFilesFolder) {
    // A buffer uri that is absolute, or climbs out with ../, must not be read.
    const std::string dir = iotest::temp_dir();
    std::filesystem::create_directories(dir + "/inner");
    iotest::write_bytes(dir + "/secret.bin", std::string(36, '\x01'));
    for (const std::string uri : {"/etc/passwd", "../secret.bin"}) {
        const std::string path = dir + "/inner/escape.gltf";
        iotest::write_bytes(path, R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri +
                                      R"(", "byteLength": 36}], "meshes": []})");
        try {
            load_mesh(path);
            ADD_FAILURE() << uri << " was read";
        } catch (const DataError& e) {
            std::string m = e.what();
            EXPECT_NE(m.find(path), std::string::npos) << m;
            EXPECT_NE(m.find("outside the glTF file's folder"), std::string::npos) << m;
            EXPECT_EQ(m.find("root:"), std::string::npos) << "no content of the refused file in the message";
        }
    }
    // Beside the file is fine.
    iotest::write_bytes(dir + "/inner/ok.bin", std::string(36, '\0'));
    iotest::write_bytes(dir + "/inner/ok.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "ok.bin", "byteLength": 36}], "meshes": []})");
    try {
        load_mesh(dir + "/inner/ok.gltf");
    } catch (const DataError& e) {
        EXPECT_EQ(std::string(e.what()).find("outside"), std::string::npos) << e.what();  // "no triangles" is fine
    }
}

TEST(MeshIo, EmptyMeshFilesAreErrors) {
    const std::string dir = iotest::temp_dir();
    for (const char* name : {"e.glb", "e.obj", "e.stl", "e.gltf"}) {
        iotest::write_bytes(dir + "/" + name, "");
        try {
            load_mesh(dir + "/" + name);
            ADD_FAILURE() << name << " loaded";
        } catch (const DataError& e) {
            EXPECT_NE(std::string(e.what()).find("the file is empty"), std::string::npos) << e.what();
        }
    }
}

// Vertex clustering (the wall's simplification in aorta_backface): a finely tessellated sphere
// keeps its shape, its winding and no degenerate or repeated triangle; cell 0 is the mesh as is.
TEST(MeshSimplify, ClusteringKeepsShapeWindingAndDropsCollapsedTriangles) {
    Mesh m;
    const int rings = 60, segs = 120;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segs; ++j) {
            const double th = M_PI * i / rings, ph = 2 * M_PI * j / segs;
            m.position.push_back(glm::vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)) * 10.0f);
        }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segs; ++j) {
            const uint32_t a = uint32_t(i * segs + j), b = uint32_t(i * segs + (j + 1) % segs);
            const uint32_t c = a + uint32_t(segs), d = b + uint32_t(segs);
            m.index.insert(m.index.end(), {a, c, b, b, c, d});  // outward (counter-clockwise seen from outside)
        }
    m.compute_normals();
    auto volume = [](const Mesh& x) {
        double v = 0;
        for (size_t t = 0; t + 2 < x.index.size(); t += 3)
            v += glm::dot(glm::dvec3(x.position[x.index[t]]),
                          glm::cross(glm::dvec3(x.position[x.index[t + 1]]), glm::dvec3(x.position[x.index[t + 2]])));
        return v / 6.0;
    };
    const Mesh s = m.simplified(1.5f);
    EXPECT_LT(s.index.size(), m.index.size() / 3) << "a 1.5-unit cell on a 10-unit sphere removes most triangles";
    EXPECT_GT(s.index.size(), 300u);
    EXPECT_NEAR(volume(s) / volume(m), 1.0, 0.08) << "shape and winding kept";
    std::set<std::array<uint32_t, 3>> seen;
    for (size_t t = 0; t + 2 < s.index.size(); t += 3) {
        std::array<uint32_t, 3> k{s.index[t], s.index[t + 1], s.index[t + 2]};
        ASSERT_TRUE(k[0] != k[1] && k[1] != k[2] && k[0] != k[2]) << "collapsed triangle " << t / 3;
        std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
        ASSERT_TRUE(seen.insert(k).second) << "repeated triangle " << t / 3;
        for (uint32_t v : k) ASSERT_LT(v, s.position.size());
    }
    ASSERT_EQ(s.normal.size(), s.position.size());
    EXPECT_EQ(m.simplified(0.0f).index, m.index) << "cell 0: unchanged";
}

// A fuzzer finding (tinygltf copies a buffer from past the end of the file when the BIN chunk
// claims more bytes than remain): the container is checked first, with the chunk and byte.
TEST(IoMesh, GlbChunkPastTheEndIsAClearErrorNotAnOverread) {
    const std::string src = std::string(PATHLET_SOURCE_DIR) + "/tests/fuzz/regressions/glb/bin_chunk_past_end.glb";
    std::string dir = iotest::temp_dir();
    iotest::write_bytes(dir + "/cut.glb", iotest::read_bytes(src));
    try {
        load_mesh(dir + "/cut.glb");
        FAIL() << "a chunk past the end must be refused";
    } catch (const DataError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("cut.glb"), std::string::npos) << m;
        EXPECT_NE(m.find("byte 548"), std::string::npos) << m;
        EXPECT_NE(m.find("claims 104 bytes, only 96 remain"), std::string::npos) << m;
    }
    std::string bytes = iotest::read_bytes(src);
    bytes[8] = char(0xff);  // the header declares more bytes than the file has
    iotest::write_bytes(dir + "/long.glb", bytes);
    EXPECT_THROW(load_mesh(dir + "/long.glb"), DataError);
}
