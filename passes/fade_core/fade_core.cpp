// fade_core: the opaque core of opacity-faded pathlets as a LineAO G-buffer: the fragments where
// the pass's colour hook — the same fade a list pass applies to opacity, by default the study's
// end fade (fade_opacity.frag) — reaches core_alpha. LineAO computed on it belongs to geometry
// that is actually visible, so resolve_list (and the other variant2 resolves) apply it per
// fragment. Give it the graph's color_hook and a researcher's fade decides the core too.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

namespace {

class FadeCore : public pathlet::lines::GBufferPass {
protected:
    std::vector<std::string> fragment_defines(const pathlet::PassContext&) const override { return {"LINE_CORE"}; }
};

}  // namespace

PATHLET_PLUGIN("fade_core", {
    sink->add(pathlet::lines::gbuffer_pass_type("fade_core",
                                                "the opaque core of opacity-faded pathlets (the colour hook's opacity "
                                                ">= core_alpha) as LineAO's G-buffer, for per-fragment AO in the "
                                                "variant2 resolves",
                                                {.color = "fade_opacity.frag"})
                  .param_float("core_alpha", 0.5, 0.0, 1.0,
                               "opacity of the colour hook from which a fragment belongs to the core (LineAO's "
                               "geometry); the fainter rest is left out")
                  .make<FadeCore>());
})
