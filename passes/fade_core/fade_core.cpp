// fade_core: the opaque core of opacity-faded pathlets as a LineAO G-buffer: fragments whose
// end fade (the same one fill_list applies to opacity) reaches core_alpha. LineAO computed on
// it belongs to geometry that is actually visible, so resolve_list can apply it per fragment.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

namespace {

namespace lines = pathlet::lines;

// core_alpha reaches fade_core.frag's u_core_alpha by declaration.
class FadeCore : public lines::EndFadePass {
public:
    FadeCore() : EndFadePass({.color = "fade_core.frag"}) {}
};

pathlet::PassTypeInfo fade_core_type() {
    auto b = lines::gbuffer_pass_type("fade_core",
                                      "the opaque core of opacity-faded pathlets (fade >= core_alpha) as LineAO's "
                                      "G-buffer, for per-fragment AO in resolve_list");
    return lines::declare_fade_params(b, 0.5, 0.15, "opacity")
        .param_float("core_alpha", 0.5, 0.0, 1.0, "opacity from which a fragment belongs to the core")
        .make<FadeCore>();
}

}  // namespace

PATHLET_PLUGIN("fade_core", { sink->add(fade_core_type()); })
