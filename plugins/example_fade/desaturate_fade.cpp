// A fade strategy in one small plugin: pathlets lose their colour with age. The line kit
// (pathlet/lines.hpp) draws the pathlets and writes LineAO's G-buffer; this pass adds only a
// colour hook (desaturate_color.frag) and its parameters, which reach the hook's uniforms
// u_start, u_grey and u_dither by declaration.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

PATHLET_PLUGIN("desaturate_fade", {
    sink->add(pathlet::lines::gbuffer_pass_type("desaturate_fade",
                                                "pathlets fade to grey with age (an out-of-tree example fade)",
                                                {.color = "desaturate_color.frag"})
                  .param_float("start", 0.3, 0.0, 1.0, "age where the fade begins (0 = the head, 1 = the tail)")
                  .param_color("grey", {0.75f, 0.75f, 0.75f}, "colour a pathlet's tail fades to")
                  .param_bool("dither", false, "also fade out by screen-door opacity (the kit dithers alpha)")
                  .make<pathlet::lines::GBufferPass>());
})
