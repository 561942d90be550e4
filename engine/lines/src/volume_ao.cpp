// The C++ side of line_volume_ao.glsl: its parameters, declared once, its uniforms and the
// 3D texture its density fetches read.
#include "saved_bindings.hpp"

#include <pathlet/lines.hpp>
#include <pathlet/shader.hpp>

#include <glm/matrix.hpp>

#include <cstdio>
#include <stdexcept>

namespace pathlet::lines {

PassTypeBuilder& declare_volume_ao_params(PassTypeBuilder& b) {
    return b
        .param_float("reach", 10.0, 0.0, 1000.0,
                     "ray length in line widths: occluders farther away do not count (the ray-traced reference's "
                     "--max-distance, 10)")
        .param_float("ao_scale", 1.15, 0.0, 10.0,
                     "k, the calibration of the crossing rate: 1 counts pathlets as randomly oriented tubes; "
                     "1.15 matches the ray-traced AO on the study phantom (see passes/volume_ao/README.md)")
        .param_enum("rays", "section", {"section", "hemisphere"},
                    "the rays: section = in the tube's cross-section, the rest of the hemisphere integrated as if "
                    "the neighbours ran parallel (bundles; phantom 1280x720, 8 rays: MAE 0.059 against the ray-traced "
                    "AO, 0.067 over the hemisphere); hemisphere = a cosine-weighted set over the whole hemisphere, "
                    "no assumption")
        .param_int("directions", 12, 1, 64, "ray directions per point (12 section rays: the ray-traced AO within MAE 0.05 at 1280x720)")
        .param_int("steps", 8, 1, 64, "density samples per ray")
        .param_enum("density_copy", "auto", {"auto", "compute", "upload"},
                    "how the density cells become the 3D texture every frame: compute = a dispatch on the GPU; "
                    "upload = a pixel-buffer upload, which a GPU driver may convert on the CPU after waiting for the "
                    "splat; auto = compute on a GPU, upload on a software rasterizer (llvmpipe, 720p: volume_ao "
                    "27-31 ms with upload, 33-51 with compute); the same texture either way");
}

std::vector<std::string> density_defines(const PassContext& ctx) {
    char scale[32];
    std::snprintf(scale, sizeof scale, "%.1f", kDensityScale);
    const PassTypeInfo* type = ctx.params().type();
    const PinDecl* pin = type ? type->pin(kDensityPin) : nullptr;
    const int binding = pin && pin->kind == PinKind::Buffer ? ctx.buffer_binding(kDensityPin) : 0;
    return {"LINE_DENSITY_BINDING " + std::to_string(binding), std::string("LINE_DENSITY_SCALE ") + scale};
}

std::vector<std::string> VolumeAo::defines(const PassContext& ctx) {
    const Params& p = ctx.params();
    std::vector<std::string> d = density_defines(ctx);
    d.push_back("VAO_DIRECTIONS " + std::to_string(p.i("directions")));
    d.push_back("VAO_STEPS " + std::to_string(p.i("steps")));
    if (p.s("rays") == "section") d.push_back("VAO_SECTION");
    return d;
}

VolumeAo::~VolumeAo() {
    if (texture_) glDeleteTextures(1, &texture_);
}

// density_copy resolved on this context's renderer (auto: compute on a GPU).
static bool copy_on_gpu(const PassContext& ctx) {
    const std::string mode = ctx.params().s("density_copy");
    if (mode != "auto") return mode == "compute";
    // Asked of GL once a process, not every frame (a glGet is a round trip to a threaded
    // driver); a process renders with one driver.
    static const bool gpu = [] {
        const GLubyte* r = glGetString(GL_RENDERER);
        return software_rasterizer(r ? reinterpret_cast<const char*>(r) : "").empty();
    }();
    return gpu;
}

void VolumeAo::bind(PassContext& ctx, const ShaderProgram& prog) {
    const std::string pin = kDensityPin;
    const Params& p = ctx.params();
    const float width = line_width(ctx);
    prog.set("u_vao_reach", p.f("reach") * width);
    prog.set("u_vao_scale", p.f("ao_scale"));
    prog.set("u_vao_radius", 0.5f * width);
    const Camera& cam = ctx.camera();
    prog.set("u_vao_inv_view", glm::inverse(cam.view));
    prog.set("u_vao_depth_range", glm::vec2(cam.near_plane, cam.far_plane));
    prog.set("u_vao_proj", glm::vec4(cam.proj[0][0], cam.proj[1][1], cam.proj[3][0], cam.proj[3][1]));
    prog.set("u_vao_perspective", cam.proj[2][3] < -0.5f ? 1 : 0);
    prog.set("u_vao_inv_size", 1.0f / glm::vec2(ctx.output_size()));
    const Buffer volume = ctx.buffer(pin);

    // The grid's size from the header. It changes only with the builder's setup, which sizes the
    // buffer by the grid: read back (a wait for the builder) only for a new buffer or size.
    if (volume.id != header_of_ || volume.bytes != header_bytes_) {
        header_ = glm::ivec4(0);
        if (volume.bytes >= kDensityHeaderBytes) glGetNamedBufferSubData(volume.id, 0, sizeof header_, &header_);
        header_of_ = volume.id;
        header_bytes_ = volume.bytes;
    }
    const glm::ivec4 dims = header_;
    const size_t cells = size_t(std::max(dims.x, 0)) * size_t(std::max(dims.y, 0)) * size_t(std::max(dims.z, 0));
    if (dims.w != 1 || cells == 0 || kDensityHeaderBytes + 4 * cells > volume.bytes)
        throw std::runtime_error("input '" + pin + "' holds no line-density volume (connect a line_density output)");
    if (glm::ivec3(dims) != dims_) {
        if (texture_) glDeleteTextures(1, &texture_);
        glCreateTextures(GL_TEXTURE_3D, 1, &texture_);
        glTextureStorage3D(texture_, 1, GL_R32F, dims.x, dims.y, dims.z);
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(texture_, wrap, GL_CLAMP_TO_EDGE);
        dims_ = glm::ivec3(dims);
    }
    if (copy_on_gpu(ctx)) {
        // Buffer to texture in a dispatch (line_density_texture.comp), with the pass's bindings kept.
        const SavedBindings saved(0, SavedBindings::kNone, 0);  // image unit 0 only
        ShaderProgram& convert = ctx.program({"line_density_texture.comp"}, density_defines(ctx));
        convert.use();
        convert.set_unit("u_density_target", 0);
        glBindImageTexture(0, texture_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        glDispatchCompute(GLuint((dims.x + 3) / 4), GLuint((dims.y + 3) / 4), GLuint((dims.z + 3) / 4));
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        saved.restore();
        prog.use();
    } else {
        // Buffer to texture through the pixel-unpack path: uint read as normalised (value / (2^32 - 1)) float.
        glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, volume.id);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage3D(texture_, 0, 0, 0, 0, dims.x, dims.y, dims.z, GL_RED, GL_UNSIGNED_INT,
                            reinterpret_cast<const void*>(kDensityHeaderBytes));
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
    prog.bind_texture("u_density_cells", texture_);
}

}  // namespace pathlet::lines
