// The line kit's hook interface: what a width or colour hook sees of one point of a pathlet.
// A hook is its own shader file that defines one function (the kit puts this file and the
// version line before it; including it again is harmless):
//   width hook (.geom, or .glsl):  float line_width_hook(LinePoint p);   // multiplier of the width, 0..4
//   colour hook (.frag, or .glsl): vec4 line_color_hook(vec4 rgba, LinePoint p);  // colour, opacity
// A kit pass names it in its color_hook / width_hook parameter; the kit links it into the
// program beside its own stages (line_quad.geom calls the width hook at every quad corner,
// line_gbuffer.frag, fill_list and isl call the colour hook per fragment). The kit's values
// (window, speed range, typical pathlet length, ...) are in line_kit_block.glsl, included here.
//
// A hook's parameters are declared once, in the hook, on the line of their uniform:
//   uniform float|int u_<name>;  // @param DEFAULT [MIN, MAX] [px] "doc"
//   uniform bool u_<name>;       // @param true|false "doc"
//   uniform int u_<name>;        // @param CHOICE {CHOICE, CHOICE, ...} "doc"   (the choice's index)
//   uniform vec3 u_<name>;       // @param [X, Y, Z] "doc"  or  @param color #rrggbb "doc"
// They become parameters of the pass (validated, --set pass.<name>=..., `pathlet passes
// --describe`, the viewer's panels) and reach u_<name> by declaration. `px`: a length in pixels.
// The defaults are line_width_default.geom and line_color_default.frag (no parameters).
#ifndef PATHLET_LINE_HOOKS_GLSL
#define PATHLET_LINE_HOOKS_GLSL

#include "line_kit_block.glsl"

struct LinePoint {
    float time;           // data time of the point, seconds
    float age;            // 0 at the pathlet's head (the current time), 1 at its tail (time - window);
                          // drawing whole lines (window <= 0): 0 at the line's last point, 1 at its first
    float arc_from_head;  // arc length from the pathlet's head, world units (>= 0)
    float arc_from_tail;  // arc length from the pathlet's tail; head + tail = the pathlet's length
    float speed;          // |velocity|, data units per second
    int line_id;          // index of the line in the data set
    float arc;            // arc length from the line's first point: where on its line the point is,
                          // whatever the window (per-segment data of a line, e.g. optimized opacity)
    vec3 position;        // data coordinates (on the quad: within half a line width of the line)
};

#endif
