// The opaque core's AO per fragment for blend-only OIT passes (shaders/oit_blend.glsl, CORE_AO):
// declared once for wboit_accum, mboit_accum and mlab_blend.
#include <pathlet/lines.hpp>

#include <stdexcept>

namespace pathlet::lines {

PassTypeBuilder& declare_core_ao_inputs(PassTypeBuilder& b) {
    return b
        .param_float("ao_tolerance", 0.004, 0.0, 1.0,
                     "with ao/core connected: a fragment within this linear depth of the core surface gets its AO; "
                     "fragments in front of the core (faded ones) and behind it stay unoccluded")
        .input_texture("ao", "r16f", "smoothed AO of the opaque core (bilateral's ao_smooth)", {.optional = true})
        .input_texture("core", "rgba16f", "normal + linear depth of the opaque core (fade_core, drawing the same lines: "
                       "every parameter the two share must agree)",
                       {.optional = true, .same_params = {"*"}});
}

std::vector<std::string> core_ao_defines(const PassContext& ctx) {
    if (ctx.connected("ao") != ctx.connected("core"))
        throw std::runtime_error("connect both 'ao' and 'core' (the core's normal_depth) or neither");
    if (!ctx.connected("ao")) return {};
    return {"CORE_AO"};
}

}  // namespace pathlet::lines
