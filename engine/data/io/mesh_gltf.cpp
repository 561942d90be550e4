// glTF 2.0 (.gltf / .glb) through tinygltf. Reading walks the default scene's node tree,
// applying node transforms; only TRIANGLES primitives with float VEC3 positions are used.
// This is the one translation unit that compiles tinygltf's implementation.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_USE_CPP14
#include <tiny_gltf.h>

#include "byte_reader.hpp"
#include "mesh_formats.hpp"

#include <glm/gtc/type_ptr.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace pathlet::io {

namespace {

struct GltfReader {
    const tinygltf::Model& model;
    const std::string& file;
    LoadReport& report;
    Mesh out;
    size_t skipped_primitives = 0;

    [[noreturn]] void fail(const std::string& m) const { fail_at(file, "glTF", m); }

    // Start of element i of an accessor, bounds-checked against its buffer.
    const unsigned char* element_base(const tinygltf::Accessor& a, size_t elem_size, size_t& stride) const {
        if (a.sparse.isSparse) fail("sparse accessors are not supported");
        if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size()) fail("accessor without a valid bufferView");
        const auto& bv = model.bufferViews[size_t(a.bufferView)];
        if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size()) fail("bufferView without a valid buffer");
        const auto& buf = model.buffers[size_t(bv.buffer)].data;
        stride = bv.byteStride ? bv.byteStride : elem_size;
        uint64_t start = uint64_t(bv.byteOffset) + a.byteOffset;
        uint64_t need = a.count ? start + uint64_t(stride) * (a.count - 1) + elem_size : start;
        if (need > buf.size() || bv.byteOffset + bv.byteLength > buf.size())
            fail("accessor '" + a.name + "' reads " + std::to_string(need) + " bytes of a " + std::to_string(buf.size()) +
                 "-byte buffer (truncated or corrupt)");
        return buf.data() + start;
    }

    std::vector<glm::vec3> vec3s(int accessor) const {
        if (accessor < 0 || size_t(accessor) >= model.accessors.size()) fail("attribute refers to a missing accessor");
        const auto& a = model.accessors[size_t(accessor)];
        if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail("only float VEC3 positions/normals are supported (accessor '" + a.name + "')");
        size_t stride;
        const unsigned char* p = element_base(a, 12, stride);
        std::vector<glm::vec3> v(a.count);
        for (size_t i = 0; i < a.count; ++i) std::memcpy(&v[i], p + i * stride, 12);
        return v;
    }

    std::vector<uint32_t> indices(int accessor) const {
        if (accessor < 0 || size_t(accessor) >= model.accessors.size()) fail("indices refer to a missing accessor");
        const auto& a = model.accessors[size_t(accessor)];
        size_t size = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                  : 0;
        if (!size || a.type != TINYGLTF_TYPE_SCALAR) fail("indices must be unsigned byte/short/int scalars");
        size_t stride;
        const unsigned char* p = element_base(a, size, stride);
        std::vector<uint32_t> v(a.count);
        for (size_t i = 0; i < a.count; ++i) {
            uint32_t x = 0;
            std::memcpy(&x, p + i * stride, size);  // little-endian
            v[i] = x;
        }
        return v;
    }

    void add_mesh(int mi, const glm::mat4& xf) {
        if (mi < 0 || size_t(mi) >= model.meshes.size()) fail("node refers to a missing mesh");
        glm::mat3 nxf = glm::transpose(glm::inverse(glm::mat3(xf)));
        for (const auto& prim : model.meshes[size_t(mi)].primitives) {
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) { ++skipped_primitives; continue; }
            auto pit = prim.attributes.find("POSITION");
            if (pit == prim.attributes.end()) { ++skipped_primitives; continue; }
            auto pos = vec3s(pit->second);
            std::vector<glm::vec3> nrm;
            auto nit = prim.attributes.find("NORMAL");
            if (nit != prim.attributes.end()) nrm = vec3s(nit->second);
            if (!nrm.empty() && nrm.size() != pos.size()) fail("NORMAL count differs from POSITION count");
            std::vector<uint32_t> idx;
            if (prim.indices >= 0) idx = indices(prim.indices);
            else for (uint32_t i = 0; i < pos.size(); ++i) idx.push_back(i);
            if (idx.size() % 3) fail("TRIANGLES primitive with " + std::to_string(idx.size()) + " indices (not a multiple of 3)");
            uint32_t base = uint32_t(out.position.size());
            // Normals only survive when every primitive has them.
            bool keep_normals = !nrm.empty() && out.normal.size() == out.position.size();
            if (!keep_normals) out.normal.clear();
            for (size_t i = 0; i < pos.size(); ++i) {
                out.position.push_back(glm::vec3(xf * glm::vec4(pos[i], 1.0f)));
                if (keep_normals) out.normal.push_back(glm::normalize(nxf * nrm[i]));
            }
            for (auto i : idx) {
                if (i >= pos.size()) fail("index " + std::to_string(i) + " >= " + std::to_string(pos.size()) + " vertices");
                out.index.push_back(base + i);
            }
        }
    }

    void visit(int ni, glm::mat4 parent, int depth) {
        if (ni < 0 || size_t(ni) >= model.nodes.size() || depth > 64) fail("bad node reference (or a cycle in the node tree)");
        const auto& n = model.nodes[size_t(ni)];
        glm::mat4 local(1.0f);
        if (n.matrix.size() == 16) {
            for (int i = 0; i < 16; ++i) glm::value_ptr(local)[i] = float(n.matrix[size_t(i)]);
        } else {
            glm::mat4 t(1.0f), r(1.0f), s(1.0f);
            if (n.translation.size() == 3) t = glm::translate(glm::mat4(1.0f), glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
            if (n.rotation.size() == 4) r = glm::toMat4(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
            if (n.scale.size() == 3) s = glm::scale(glm::mat4(1.0f), glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
            local = t * r * s;
        }
        glm::mat4 xf = parent * local;
        if (n.mesh >= 0) add_mesh(n.mesh, xf);
        for (int c : n.children) visit(c, xf, depth + 1);
    }

    Mesh run() {
        if (!model.scenes.empty()) {
            size_t si = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? size_t(model.defaultScene) : 0;
            for (int n : model.scenes[si].nodes) visit(n, glm::mat4(1.0f), 0);
        } else {
            for (size_t m = 0; m < model.meshes.size(); ++m) add_mesh(int(m), glm::mat4(1.0f));
        }
        if (skipped_primitives)
            report.warnings.push_back("skipped " + std::to_string(skipped_primitives) + " non-triangle primitives");
        return std::move(out);
    }
};

}  // namespace

namespace {

// External buffers and images stay inside the glTF file's own folder: a uri that is absolute
// or climbs out with ../ could read any file the user can (/etc/passwd as vertex data, or its
// size leaked through a byteLength error). PATHLET_GLTF_ALLOW_OUTSIDE=1 lifts the fence.
struct Fence {
    std::filesystem::path root;
    bool allow_outside = false;
    std::string refused;  // the first path refused, for the error message

    bool inside(const std::string& path) {
        if (allow_outside) return true;
        std::error_code ec;
        const auto p = std::filesystem::weakly_canonical(path, ec).lexically_normal();
        const auto rel = p.lexically_relative(root);
        bool ok = !ec && !rel.empty() && *rel.begin() != ".." && !rel.is_absolute();
        if (!ok && refused.empty()) refused = path;
        return ok;
    }
};

bool fenced_exists(const std::string& path, void* user) {
    return static_cast<Fence*>(user)->inside(path) && tinygltf::FileExists(path, nullptr);
}
bool fenced_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    if (!static_cast<Fence*>(user)->inside(path)) {
        if (err) *err += "refused to read '" + path + "': outside the glTF file's folder";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

// The GLB container, checked before tinygltf sees it: tinygltf trusts the BIN chunk's length
// and copies a buffer from past the end of the file when the chunk claims more bytes than
// there are (a fuzzer finding: tests/fuzz/regressions/glb/bin_chunk_past_end.glb).
void check_glb_container(std::string_view bytes, const std::string& file) {
    auto u32 = [&](size_t at) {
        uint32_t v = 0;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;  // GLB is little-endian, as every platform Pathlet builds on
    };
    if (bytes.size() < 12 || bytes.substr(0, 4) != "glTF") fail_at(file, "GLB header", "not a GLB file (no 'glTF' magic)");
    if (u32(4) != 2) fail_at(file, "GLB header", "version " + std::to_string(u32(4)) + ", expected 2");
    const size_t total = u32(8);
    if (total > bytes.size())
        fail_at(file, "GLB header", "declares " + std::to_string(total) + " bytes, the file has " +
                                        std::to_string(bytes.size()) + " (truncated?)");
    for (size_t at = 12, k = 0; at < total; ++k) {
        if (total - at < 8) fail_at(file, at_byte(at), "chunk header cut off by the end of the GLB");
        const size_t len = u32(at);
        if (len > total - at - 8)
            fail_at(file, at_byte(at), "chunk " + std::to_string(k) + " claims " + std::to_string(len) +
                                           " bytes, only " + std::to_string(total - at - 8) + " remain");
        at += 8 + len;
    }
}

}  // namespace

Mesh read_gltf(std::string_view bytes, bool binary, const std::string& file, LoadReport& report) {
    if (binary) check_glb_container(bytes, file);
    report.format = binary ? "glTF 2.0 binary (.glb)" : "glTF 2.0";
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    std::string base = std::filesystem::path(file).parent_path().string();
    Fence fence;
    std::error_code ec;
    fence.root = std::filesystem::weakly_canonical(base.empty() ? "." : base, ec).lexically_normal();
    const char* allow = std::getenv("PATHLET_GLTF_ALLOW_OUTSIDE");
    fence.allow_outside = allow && std::string(allow) == "1";
    loader.SetFsCallbacks({&fenced_exists, &tinygltf::ExpandFilePath, &fenced_read, &tinygltf::WriteWholeFile, &fence});
    bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                   unsigned(bytes.size()), base)
                     : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
    if (!fence.refused.empty())
        fail_at(file, "glTF", "external file '" + fence.refused + "' is outside the glTF file's folder " +
                                  fence.root.string() + "; buffers and images must lie beside it (set "
                                  "PATHLET_GLTF_ALLOW_OUTSIDE=1 to allow other folders)");
    if (!ok) fail_at(file, "glTF", "cannot parse: " + (err.empty() ? std::string("unknown tinygltf error") : err));
    if (!warn.empty()) report.warnings.push_back("tinygltf: " + warn);
    Mesh m = GltfReader{model, file, report, {}, 0}.run();
    finish_mesh(m, report, file);
    return m;
}

std::string write_gltf(const Mesh& m, bool binary, const std::string& file) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "pathlet";
    tinygltf::Buffer buf;
    auto append = [&](const void* p, size_t n) {
        size_t at = buf.data.size();
        buf.data.resize(at + ((n + 3) & ~size_t(3)), 0);
        std::memcpy(buf.data.data() + at, p, n);
        return at;
    };
    auto view = [&](size_t offset, size_t length, int target) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = offset;
        v.byteLength = length;
        v.target = target;
        model.bufferViews.push_back(v);
        return int(model.bufferViews.size() - 1);
    };
    auto accessor = [&](int bv, int comp, int type, size_t count) {
        tinygltf::Accessor a;
        a.bufferView = bv;
        a.componentType = comp;
        a.type = type;
        a.count = count;
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    };
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    size_t n = m.position.size();
    int pa = accessor(view(append(m.position.data(), n * 12), n * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    Bounds b = m.bounds();
    if (n) {
        model.accessors[size_t(pa)].minValues = {b.lo.x, b.lo.y, b.lo.z};  // required by the spec
        model.accessors[size_t(pa)].maxValues = {b.hi.x, b.hi.y, b.hi.z};
    }
    prim.attributes["POSITION"] = pa;
    if (m.normal.size() == n && n)
        prim.attributes["NORMAL"] = accessor(view(append(m.normal.data(), n * 12), n * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
    prim.indices = accessor(view(append(m.index.data(), m.index.size() * 4), m.index.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, m.index.size());
    model.buffers.push_back(std::move(buf));
    tinygltf::Mesh mesh;
    mesh.name = std::filesystem::path(file).stem().string();
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    std::ostringstream os;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, os, !binary, binary)) fail_at(file, "glTF", "tinygltf could not serialise the mesh");
    return os.str();
}

}  // namespace pathlet::io
