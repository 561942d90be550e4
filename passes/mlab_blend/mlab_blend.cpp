// mlab_blend: multi-layer alpha blending (Salvi & Vaidyanathan, I3D 2014) with a depth bucket
// (Kern et al., IEEE TVCG 27(8), 2021: MLABDB), the gather and the resolve. Per pixel a front
// bucket and `layers` nodes (premultiplied colour and opacity, depth; 8 bytes each) in a storage
// buffer: a fragment behind the pixel's nearest opaque one (mlab_bucket) is dropped, one in front
// of the first substantial one is blended into the front bucket, any other is inserted into the
// depth-sorted nodes, and when they overflow the last two merge. That read-modify-write must run
// in raster order per pixel: GL_ARB_fragment_shader_interlock (ordered). A driver without it
// (llvmpipe) fails here, at setup, with one line; no fallback is used (a spinlock is not
// deadlock-free where fragments of one pixel share a SIMD group, and MLAB's merge depends on the
// order). Then a fullscreen resolve composites bucket and nodes front to back.
#include <pathlet/gl_limits.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace lines = pathlet::lines;

constexpr const char* kInterlock = "GL_ARB_fragment_shader_interlock";
constexpr size_t kNodeBytes = 8;  // uvec2: packUnorm4x8(premultiplied rgb, alpha), depth + 1 as float bits

bool has_extension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && std::strcmp(e, name) == 0) return true;
    }
    return false;
}

class MlabBlend : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        // The size first: a picture the nodes cannot hold is refused on every driver alike.
        const glm::ivec2 size = ctx.output_size();
        pathlet::check_storage_block(node_bytes(ctx), "mlab_blend's nodes (" + std::to_string(ctx.params().i("layers")) +
                                                           " layers and the front bucket, 8 bytes each a pixel)",
                                     pathlet::at_picture_size(size.x, size.y), "fewer layers or a smaller picture fit");
        if (!has_extension(kInterlock)) {
            const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
            std::string driver = renderer ? renderer : "unknown";
            driver = driver.substr(0, driver.find(" ("));  // "llvmpipe (LLVM 15.0.6, 256 bits)" -> "llvmpipe"
            throw std::runtime_error(std::string("MLAB needs ") + kInterlock + ", which this driver (" + driver +
                                     ") lacks; variant2_exact, variant2_mboit and variant2_wboit need none");
        }
        const int layers = ctx.params().i("layers");
        std::vector<std::string> defines = lines::core_ao_defines(ctx);
        defines.push_back("MLAB_LAYERS " + std::to_string(layers));
        gather_ = &lines::program(ctx, {"mlab_gather.frag"}, lines::hooks(ctx), defines);
        resolve_ = &ctx.program({"fullscreen.vert", "mlab_resolve.frag"}, {"MLAB_LAYERS " + std::to_string(layers)});
        drawer_.set_depth_func(GL_ALWAYS);
        drawer_.set_occlusion_culling(false);
    }

    void execute(pathlet::PassContext& ctx) override {
        const glm::ivec2 size = ctx.output_size();
        const pathlet::Buffer nodes = ctx.grow_buffer("nodes", node_bytes(ctx));
        const GLuint zero = 0;
        // The last frame's gather wrote the nodes as a storage block: its writes land before
        // the clear only behind a buffer-update barrier.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glClearNamedBufferData(nodes.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);  // every slot empty
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        ctx.bind_framebuffer({});  // no attachments: the nodes are the pass's only writes
        gather_->use();
        gather_->set("u_width", size.x);
        drawer_.draw(ctx, *gather_);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        ctx.bind_framebuffer({"color"});
        resolve_->use();
        resolve_->set("u_width", size.x);
        ctx.draw_fullscreen();
        ctx.stat("node_memory_mib", double(nodes.bytes) / 1048576.0);
    }

private:
    static size_t node_bytes(const pathlet::PassContext& ctx) {
        const glm::ivec2 size = ctx.output_size();
        const size_t slots = size_t(ctx.params().i("layers")) + 1;  // the front bucket and the nodes
        return size_t(size.x) * size_t(size.y) * slots * kNodeBytes;
    }

    pathlet::ShaderProgram* gather_ = nullptr;
    pathlet::ShaderProgram* resolve_ = nullptr;
    lines::Drawer drawer_;
};

pathlet::PassTypeInfo mlab_blend_type() {
    pathlet::PassTypeBuilder b("mlab_blend",
                               "MLAB with depth buckets (Kern et al. 2021): the window's fragments into a front bucket "
                               "and `layers` depth-sorted nodes per pixel, merged on overflow, then composited; needs "
                               "GL_ARB_fragment_shader_interlock (fails at setup without it)");
    lines::declare_params(b, {.color = "fade_opacity.frag"})
        .param_int("layers", 4, 1, 8, "nodes per pixel behind the front bucket (8 bytes each; Kern et al.: 4)")
        .param_color("background", {1.0f, 1.0f, 1.0f}, "colour behind all fragments")
        .input_texture("bucket", "rg32f", "mlab_bucket's depths: the front bucket's end and the nearest opaque fragment "
                       "(of the same fragments: every parameter the two passes share must agree)",
                       {.same_params = {"*"}})
        .internal_buffer("nodes", "per pixel the front bucket and the layers (8 bytes each), cleared every frame",
                         {.bytes = 16})
        .output_texture("color", "rgba8", "composited colour, alpha 1 where any fragment landed");
    lines::declare_core_ao_inputs(b);
    return b.make<MlabBlend>();
}

}  // namespace

PATHLET_PLUGIN("mlab_blend", { sink->add(mlab_blend_type()); })
