// The edge record: what a line pass's optional `edge` output (rgba8) holds per pixel about the
// front line's nearer edge, a rim or a pathlet's end, for edge_aa. Written by the line kit
// (line_edge in line_common.glsl), read by edge_aa; this file is their one definition of it.
//   rg: 0.5 + 0.5 * the outward screen direction through the edge
//   b:  the distance from the pixel centre to the edge in pixels / 2 (clamped to 1)
//   a:  0 = no line; else 0.2 + 0.8 * the line's width in pixels / 4 (clamped; an end: 1), so
//       the far rim of a line thinner than a pixel bounds its coverage
#ifndef PATHLET_LINE_EDGE_RECORD_GLSL
#define PATHLET_LINE_EDGE_RECORD_GLSL

struct LineEdge {
    bool line;    // a line covers the pixel's centre
    vec2 dir;     // outward, about unit length
    float dist;   // pixels to the edge
    float width;  // pixels across the line (at most 4)
};

vec4 line_edge_encode(vec2 dir, float dist_px, float width_px) {
    return vec4(0.5 + 0.5 * dir, min(dist_px * 0.5, 1.0), 0.2 + 0.8 * clamp(width_px * 0.25, 0.0, 1.0));
}

LineEdge line_edge_decode(vec4 e) {
    LineEdge d;
    d.line = e.a > 0.0;
    d.dir = e.rg * 2.0 - 1.0;
    d.dist = 2.0 * e.b;
    d.width = (e.a - 0.2) * 5.0;
    return d;
}

#endif
