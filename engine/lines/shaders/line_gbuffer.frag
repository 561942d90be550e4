#version 450 core
// The line kit's G-buffer stage (LineAO's inputs) per fragment of a pathlet quad: colour (speed
// map through the pass's colour hook, then halo), view-space tube normal + normalised linear
// depth, zoom (pixels per world unit), optionally the line id, the rim for edge_aa and the
// axis for volume_ao (line_gbuffer_out.glsl). The hook's alpha becomes screen-door coverage:
// the targets are opaque, so a fading fragment survives on a share of the pixels (alpha 1
// keeps them all).
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "line_gbuffer_out.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's hook, linked in beside this file
#ifdef LINE_CORE
uniform float u_core_alpha;  // fade_core's parameter
#endif

void main() {
    LineFrag f = line_fragment();
    vec4 c = line_color_hook(vec4(f.color, 1.0), f.point);
#if defined(LINE_CORE)  // fade_core: the hook's opaque core, whole (the fade a list pass applies)
    if (c.a < u_core_alpha) discard;
#elif !defined(LINE_OPAQUE)  // the default colour hook is opaque: no screen door, no discard
    if (c.a < line_screen_door_threshold(gl_FragCoord.xy)) discard;
#endif
    line_gbuffer_write(f, c.rgb);
}
