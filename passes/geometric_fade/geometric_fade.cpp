// geometric_fade: variant 3 of the study. Pathlet ends taper in width instead of
// opacity, so the G-buffer stays opaque and LineAO needs no transparency: the line kit's
// G-buffer pass whose default width hook is the kit's taper (fade_width.geom, on the end fade's
// parameters declared in line_fade.glsl).
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

PATHLET_PLUGIN("geometric_fade", {
    sink->add(pathlet::lines::gbuffer_pass_type("geometric_fade",
                                                "variant 3 of the study: pathlet ends taper in width instead of "
                                                "opacity; writes LineAO's G-buffer like gbuffer, with tube normals and "
                                                "depth of the tapered width",
                                                {.width = "fade_width.geom"})
                  .make<pathlet::lines::GBufferPass>());
})
