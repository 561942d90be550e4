// The line kit's hook interface: what a width or colour hook sees of one point of a pathlet.
// A hook is its own shader file that includes this and defines one function:
//   width hook, a .geom file:  float line_width_hook(LinePoint p);   // multiplier of the width, 0..4
//   colour hook, a .frag file: vec4 line_color_hook(vec4 rgba, LinePoint p);
// The kit links it into the program beside its own stages (engine/lines/shaders/line_quad.geom calls the
// width hook at every quad corner; line_gbuffer.frag and isl call the colour hook per fragment).
// The defaults are engine/lines/shaders/line_width_default.geom and engine/lines/shaders/line_color_default.frag.
#ifndef PATHLET_LINE_HOOKS_GLSL
#define PATHLET_LINE_HOOKS_GLSL

struct LinePoint {
    float time;           // data time of the point, seconds
    float age;            // 0 at the pathlet's head (the current time), 1 at its tail (time - window);
                          // drawing whole lines (window <= 0): 0 at the line's last point, 1 at its first
    float arc_from_head;  // arc length from the pathlet's head, world units (>= 0)
    float arc_from_tail;  // arc length from the pathlet's tail; head + tail = the pathlet's length
    float speed;          // |velocity|, data units per second
    int line_id;          // index of the line in the data set
};

#endif
