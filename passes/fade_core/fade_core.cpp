// fade_core: the opaque core of opacity-faded pathlets as a LineAO G-buffer: fragments whose
// end fade (the same one fill_list applies to opacity) reaches core_alpha. LineAO computed on
// it belongs to geometry that is actually visible, so resolve_list can apply it per fragment.
// The line kit's G-buffer pass with the kit's core hook (fade_core.frag) as its colour hook.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

PATHLET_PLUGIN("fade_core", {
    sink->add(pathlet::lines::gbuffer_pass_type("fade_core",
                                                "the opaque core of opacity-faded pathlets (fade >= core_alpha) as "
                                                "LineAO's G-buffer, for per-fragment AO in resolve_list",
                                                {.color = "fade_core.frag"})
                  .make<pathlet::lines::GBufferPass>());
})
