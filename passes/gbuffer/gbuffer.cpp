// gbuffer: the pathlets of the time window as view-aligned tube quads into LineAO's inputs
// (colour map, normal + linear depth, zoom, depth, optionally line ids). It is the line
// kit's G-buffer pass with no hooks (pathlet/lines.hpp); fades are the same with a hook.
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>

PATHLET_PLUGIN("gbuffer", {
    sink->add(pathlet::lines::gbuffer_pass_type(
                  "gbuffer", "pathlets of the time window as view-aligned tube quads with halos and a speed colour "
                             "map, written as LineAO's G-buffer (colour, normal + linear depth, zoom, depth)")
                  .make<pathlet::lines::GBufferPass>());
})
