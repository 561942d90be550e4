// resolve_list: variant 2's resolve. Sorts each pixel's linked list by depth and composites it
// front to back into the colour map that bilateral multiplies LineAO into (the seed's
// variant 2), or, given an opaque core's AO, applies AO per fragment itself (variant2_oit_ao).
#include <pathlet/gpu_readback.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

namespace {

class ResolveList : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        targets_ = {"color"};
        std::vector<std::string> defines = pathlet::oit::defines();
        defines.push_back("MAX_FRAGMENTS " + std::to_string(ctx.params().i("max_fragments")));
        defines.push_back("SORT_BLOCK " + std::to_string(ctx.params().i("sort_block")));
        for (const char* pin : {"unlit", "front_alpha"})
            if (ctx.connected(pin)) {
                defines.push_back(std::string(pin == std::string("unlit") ? "UNLIT_LOCATION " : "FRONT_ALPHA_LOCATION ") +
                                  std::to_string(targets_.size()));
                targets_.push_back(pin);
            }
        vao_on_ = ctx.connected("records") && ctx.connected("density");
        if (ctx.connected("records") != ctx.connected("density"))
            throw std::runtime_error("connect both 'records' (fill_list) and 'density' (line_density) or neither");
        if (ctx.connected("front_normal_depth")) {
            if (!vao_on_) throw std::runtime_error("the front outputs need 'records' and 'density' connected");
            defines.push_back("FRONT_LOCATION " + std::to_string(targets_.size()));
            for (const char* pin : {"front_normal_depth", "front_line_id", "front_ao"}) targets_.push_back(pin);
        }
        if (vao_on_) {
            for (const std::string& d : pathlet::lines::VolumeAo::defines(ctx)) defines.push_back(d);
            defines.push_back("VOLUME_AO");
            defines.push_back("VAO_LAYERS " + std::to_string(ctx.params().i("ao_layers")));
        }
        prog_ = &ctx.program({"fullscreen.vert", "resolve_list.frag"}, defines);
        if (ctx.connected("ao") != ctx.connected("core"))
            throw std::runtime_error("connect both 'ao' and 'core' (the core's normal_depth) or neither");
        if (vao_on_ && ctx.connected("ao"))  // the shader has one source of AO per fragment
            throw std::runtime_error("connect 'ao' and 'core' (the core's AO) or 'records' and 'density' (every "
                                     "fragment's own AO), not both");
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        const GLuint nodes = ctx.buffer_texture("nodes", pathlet::oit::kNodeFormat);  // fill_list may have grown it
        const GLuint stats = ctx.buffer("stats").id;
        const GLuint zero[4] = {0, 0, 0, 0};
        glNamedBufferSubData(stats, 0, sizeof(zero), zero);
        const bool skip_empty = ctx.connected("coverage");
        if (skip_empty) {  // background everywhere first; the shader then runs on covered tiles only
            const glm::vec4 bg(p.v3("background"), 0.0f);
            const glm::vec4 none(0.0f);
            const glm::vec4 far(0.0f, 0.0f, 0.0f, 1.0f), unoccluded(1.0f);
            const GLint no_line = -1;
            for (const auto& t : targets_) {
                if (t == "front_line_id") glClearTexImage(ctx.texture(t).id, 0, GL_RED_INTEGER, GL_INT, &no_line);
                else glClearTexImage(ctx.texture(t).id, 0, GL_RGBA, GL_FLOAT,
                                     t == "front_alpha" ? &none.x
                                     : t == "front_normal_depth" ? &far.x
                                     : t == "front_ao" ? &unoccluded.x : &bg.x);
            }
        }
        ctx.bind_framebuffer(targets_, skip_empty ? "coverage" : "");
        prog_->bind_texture("u_nodes", nodes);
        prog_->use();  // heads, ao, core, stats and the parameters by declaration
        prog_->set("u_use_ao", ctx.connected("ao") ? 1 : 0);
        if (vao_on_) {
            prog_->bind_texture("u_records", ctx.buffer_texture("records", pathlet::oit::kNodeFormat));
            vao_.bind(ctx, *prog_);
        }
        if (skip_empty) {
            // Only where the lines can be (the targets were cleared): llvmpipe runs the shader on
            // every block the draw covers, depth-tested or not (62 -> 40 ms at 720p, variant2_oit_ao).
            pathlet::lines::ScopedScissor clip(pathlet::lines::screen_rect(ctx, 2));
            ctx.draw_fullscreen_on_geometry(*prog_);
        } else {
            ctx.draw_fullscreen();
        }
        // The statistics through a fenced copy, read when the GPU is done (a frame or two late
        // on a GPU): the frame loop never waits for them.
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        if (!stats_) stats_ = std::make_unique<pathlet::GpuReadback>(sizeof stats_seen_);
        if (const void* p = stats_->poll_newest()) std::memcpy(stats_seen_, p, sizeof stats_seen_);
        stats_->copy(stats, 0);
        ctx.stat("peak_nodes_per_pixel", double(stats_seen_[0]));
        ctx.stat("truncated_pixels", double(stats_seen_[1]));
    }

private:
    pathlet::ShaderProgram* prog_ = nullptr;
    std::vector<std::string> targets_;
    pathlet::lines::VolumeAo vao_;
    bool vao_on_ = false;
    std::unique_ptr<pathlet::GpuReadback> stats_;
    GLuint stats_seen_[2] = {0, 0};  // the newest statistics known
};

pathlet::PassTypeInfo resolve_list_type() {
    pathlet::PassTypeBuilder b("resolve_list",
                               "variant 2: sorts each pixel's linked list by depth (ties by line id) and composites it "
                               "front to back over the background; optionally applies an opaque core's AO, or every "
                               "fragment's own volume AO, per fragment");
    pathlet::lines::declare_line_width_params(b);
    pathlet::lines::declare_volume_ao_params(b);
    pathlet::oit::declare_sort_block(b, "; at least max_fragments: one round, the nearest max_fragments at once");
    return b
            .param_int("max_fragments", 32, 1, 64,
                       "nearest fragments kept per pixel; a longer list drops its farthest (counted as "
                       "truncated_pixels)")
            .param_float("ao_tolerance", 0.004, 0.0, 1.0,
                         "with ao/core connected: a fragment within this linear depth of the core surface gets its "
                         "AO; fragments in front of the core (faded ones) and behind it stay unoccluded")
            .param_int("ao_layers", 64, 1, 64,
                       "with records: the composited fragments (front to back) whose own AO is evaluated; those "
                       "behind take the last one's (2: RMS 2.7/255 at 720p on the phantom, 0.7x the pass)")
            .param_color("background", {1.0f, 1.0f, 1.0f}, "colour behind all fragments")
            .input_texture("heads", "r32ui", "per-pixel list heads (fill_list)")
            .input_buffer("nodes", "list nodes (fill_list)")
            .input_texture("ao", "r16f", "smoothed AO of the opaque core (bilateral's ao_smooth)", {.optional = true})
            .input_texture("core", "rgba16f", "normal + linear depth of the opaque core (fade_core)", {.optional = true})
            .input_texture("coverage", "depth24",
                           "fill_list's coverage depth: when connected, pixels without fragments are only cleared", {.optional = true})
            .input_buffer("records",
                          "fill_list's records: with density, every fragment is shaded by its own AO (fill_list's "
                          "line_width and width_factor must be this pass's)",
                          {.optional = true, .same_params = {"line_width", "width_factor"}})
            .input_buffer("density", "the line-density volume (line_density), with records", {.optional = true})
            .internal_buffer("stats", "peak list length and truncated pixels of the frame (two uints)", {.bytes = 16})
            .output_texture("color", "rgba8",
                            "composited colour, alpha 1 where any fragment landed (lit by AO when ao is connected)")
            .output_texture("unlit", "rgba8", "the same composite without AO (bind it to get it)", {.optional = true})
            .output_texture("front_alpha", "r16f", "opacity of each pixel's nearest fragment, 0 where none",
                            {.optional = true})
            .output_texture("front_normal_depth", "rgba16f",
                            "with records: the nearest fragment's view-space normal and linear depth (as a G-buffer "
                            "keeps them; background 0,0,0,1); bind all three front outputs to get them", {.optional = true})
            .output_texture("front_line_id", "r32i", "with records: the nearest fragment's line id, -1 where none", {.optional = true})
            .output_texture("front_ao", "r16f", "with records: the nearest fragment's own AO (before its end fade), 1 "
                            "where none", {.optional = true})
            .make<ResolveList>();
}

}  // namespace

PATHLET_PLUGIN("resolve_list", { sink->add(resolve_list_type()); })
