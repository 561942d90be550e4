// The edge record: what a line pass's optional `edge` output (rgba8) holds per pixel about the
// front line's nearer edge, a rim or a pathlet's end, for edge_aa. Written by the line kit
// (line_edge in line_common.glsl), read by edge_aa; this file is their one definition of it.
//   r: the outward screen direction through the edge, atan(y, x) / 2pi + 0.5
//   g: the fringe: the colour of the line's strip that covers the next pixel out, relative to
//      this pixel's colour (< 1 where that strip is darker halo than this pixel's average)
//   b: the distance from the pixel centre to the edge in pixels / 2 (clamped to 1)
//   a: 0 = no line; else 0.2 + 0.8 * the line's width in pixels / 4 (clamped; an end: 1), so the
//      far rim of a line thinner than a pixel bounds its coverage
#ifndef PATHLET_LINE_EDGE_RECORD_GLSL
#define PATHLET_LINE_EDGE_RECORD_GLSL

struct LineEdge {
    bool line;     // a line covers the pixel's centre
    vec2 dir;      // unit, outward
    float fringe;  // colour factor of the strip beyond (see g above)
    float dist;    // pixels to the edge
    float width;   // pixels across the line (at most 4)
};

vec4 line_edge_encode(vec2 dir, float fringe, float dist_px, float width_px) {
    return vec4(atan(dir.y, dir.x) * 0.15915494 + 0.5, clamp(fringe, 0.0, 1.0), min(dist_px * 0.5, 1.0),
                0.2 + 0.8 * clamp(width_px * 0.25, 0.0, 1.0));
}

LineEdge line_edge_decode(vec4 e) {
    LineEdge d;
    d.line = e.a > 0.0;
    float angle = (e.r - 0.5) * 6.2831853;
    d.dir = vec2(cos(angle), sin(angle));
    d.fringe = e.g;
    d.dist = 2.0 * e.b;
    d.width = (e.a - 0.2) * 5.0;
    return d;
}

#endif
