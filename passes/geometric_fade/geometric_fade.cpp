// geometric_fade: variant 3 of the study (seed §IV.d). Pathlet ends taper in width instead of
// opacity, so the G-buffer stays opaque and LineAO needs no transparency. It is the line kit's
// G-buffer pass with a width hook (taper_width.geom) driven by the kit's end fade.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

namespace {

namespace lines = pathlet::lines;

class GeometricFade : public lines::EndFadePass {
public:
    GeometricFade() : EndFadePass({.width = "taper_width.geom"}) {}
};

pathlet::PassTypeInfo geometric_fade_type() {
    auto b = lines::gbuffer_pass_type("geometric_fade",
                                      "variant 3 of the study: pathlet ends taper in width instead of opacity; writes "
                                      "LineAO's G-buffer like gbuffer, with tube normals and depth of the tapered width");
    return lines::declare_fade_params(b, 0.5, 0.15, "width").make<GeometricFade>();
}

}  // namespace

PATHLET_PLUGIN("geometric_fade", { sink->add(geometric_fade_type()); })
