// resolve_list: variant 2's resolve. Sorts each pixel's linked list by depth and composites it
// front to back into the colour map that bilateral multiplies LineAO into (the seed's
// variant 2), or, given an opaque core's AO, applies AO per fragment itself (variant2_oit_ao).
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <string>
#include <vector>

namespace {

constexpr GLuint kStatsBinding = 9;  // RESOLVE_STATS_BINDING: peak list length, truncated pixels

class ResolveList : public pathlet::Pass {
public:
    ~ResolveList() override {
        if (view_) glDeleteTextures(1, &view_);
        if (stats_) glDeleteBuffers(1, &stats_);
    }

    void setup(pathlet::PassContext& ctx) override {
        targets_ = {"color"};
        std::vector<std::string> defines = pathlet::oit::defines();
        defines.push_back("RESOLVE_STATS_BINDING " + std::to_string(kStatsBinding));
        for (const char* pin : {"unlit", "front_alpha"})
            if (ctx.connected(pin)) {
                defines.push_back(std::string(pin == std::string("unlit") ? "UNLIT_LOCATION " : "FRONT_ALPHA_LOCATION ") +
                                  std::to_string(targets_.size()));
                targets_.push_back(pin);
            }
        prog_ = &ctx.program({"fullscreen.vert", "resolve_list.frag"}, defines);
        if (!stats_) {
            glCreateBuffers(1, &stats_);
            glNamedBufferStorage(stats_, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
        }
        if (ctx.connected("ao") != ctx.connected("core"))
            throw std::runtime_error("connect both 'ao' and 'core' (the core's normal_depth) or neither");
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        pathlet::Buffer nodes = ctx.buffer("nodes");
        if (nodes.id != viewed_) {  // fill_list may have grown it
            if (view_) glDeleteTextures(1, &view_);
            glCreateTextures(GL_TEXTURE_BUFFER, 1, &view_);
            glTextureBuffer(view_, GL_RGBA32UI, nodes.id);
            viewed_ = nodes.id;
        }
        const GLuint zero[4] = {0, 0, 0, 0};
        glNamedBufferSubData(stats_, 0, sizeof(zero), zero);
        const bool skip_empty = ctx.connected("coverage");
        if (skip_empty) {  // background everywhere first; the shader then runs on covered tiles only
            const glm::vec4 bg(p.v3("background"), 0.0f);
            const glm::vec4 none(0.0f);
            for (const auto& t : targets_)
                glClearTexImage(ctx.texture(t).id, 0, GL_RGBA, GL_FLOAT, t == "front_alpha" ? &none.x : &bg.x);
        }
        ctx.bind_framebuffer(targets_, skip_empty ? "coverage" : "");
        prog_->bind_texture("u_nodes", view_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kStatsBinding, stats_);
        prog_->use();  // heads, ao, core and the parameters by declaration
        prog_->set("u_use_ao", ctx.connected("ao") ? 1 : 0);
        if (skip_empty) ctx.draw_fullscreen_on_geometry(*prog_);
        else ctx.draw_fullscreen();
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint s[2] = {0, 0};
        glGetNamedBufferSubData(stats_, 0, sizeof(s), s);
        ctx.stat("peak_nodes_per_pixel", double(s[0]));
        ctx.stat("truncated_pixels", double(s[1]));
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    std::vector<std::string> targets_;
    GLuint view_ = 0, viewed_ = 0, stats_ = 0;
};

}  // namespace

PATHLET_PLUGIN("resolve_list", {
    sink->add(
        pathlet::PassTypeBuilder("resolve_list",
                                 "variant 2: sorts each pixel's linked list by depth (ties by line id) and composites "
                                 "it front to back over the background; optionally applies an opaque core's AO per "
                                 "fragment")
            .param_int("max_fragments", 32, 1, 64,
                       "nearest fragments kept per pixel; a longer list drops its farthest (counted as "
                       "truncated_pixels)")
            .param_float("ao_tolerance", 0.004, 0.0, 1.0,
                         "with ao/core connected: a fragment within this linear depth of the core surface gets its "
                         "AO; fragments in front of the core (faded ones) and behind it stay unoccluded")
            .param_color("background", {1.0f, 1.0f, 1.0f}, "colour behind all fragments")
            .input_texture("heads", "r32ui", "per-pixel list heads (fill_list)")
            .input_buffer("nodes", "list nodes (fill_list)")
            .input_texture("ao", "r16f", "smoothed AO of the opaque core (bilateral's ao_smooth)", {.optional = true})
            .input_texture("core", "rgba16f", "normal + linear depth of the opaque core (fade_core)", {.optional = true})
            .input_texture("coverage", "depth24",
                           "fill_list's coverage depth: when connected, pixels without fragments are only cleared", {.optional = true})
            .output_texture("color", "rgba8",
                            "composited colour, alpha 1 where any fragment landed (lit by AO when ao is connected)")
            .output_texture("unlit", "rgba8", "the same composite without AO (bind it to get it)", {.optional = true})
            .output_texture("front_alpha", "r16f", "opacity of each pixel's nearest fragment, 0 where none", {.optional = true})
            .make<ResolveList>());
})
