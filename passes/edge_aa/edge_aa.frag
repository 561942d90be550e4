#version 450 core
// Analytic edge anti-aliasing after the lighting (distance-to-edge AA, as GPAA/DEAA): the
// G-buffer recorded, per pixel, the front line's nearer edge, a rim or a pathlet's end (outward
// direction and distance in pixels). A pixel the edge cuts is the line's colour over its share
// of the pixel (a box filter across the edge) and the colour beyond it elsewhere; a pixel just
// outside a line in front of it gets that line's share the same way. Edges against the
// background, the wall and lines behind all become smooth, and the AO, computed per pixel
// before, is untouched.
#include "fullscreen_pass.glsl"
#include "line_edge_record.glsl"

#ifdef FULLSCREEN_COMPUTE
layout(rgba8) writeonly uniform image2D u_final;
void write_final(ivec2 p, vec4 c) { imageStore(u_final, p, c); }
#else
layout(location = 0) out vec4 o_color;
void write_final(ivec2 p, vec4 c) { o_color = c; }
#endif
uniform sampler2D u_color;  // the finished image (straight alpha)
uniform sampler2D u_edge;   // the line pass's edge records (line_edge_record.glsl; not read when disabled)
uniform sampler2D u_depth;  // the G-buffer z-buffer (background 1)
uniform int u_alpha;        // 0 (opaque): flatten onto the background colour (alpha 1); 1: coverage
uniform bool u_enabled;     // false: flatten only

const ivec2 kNeighbours[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));

vec4 premultiplied(ivec2 q) {
    vec4 c = texelFetch(u_color, clamp(q, ivec2(0), textureSize(u_color, 0) - 1), 0);
    // Opaque output: straight colours mix like composited ones, because a background pixel
    // carries the background colour; coverage output: premultiply so alpha 0 adds nothing.
    return u_alpha == 0 ? vec4(c.rgb, 1.0) : vec4(c.rgb * c.a, c.a);
}

// Share of a pixel whose centre lies `inside` pixels within a line `width` pixels wide (from
// its rim), box-filtered across the line: both rims count, so a thin line never over-covers.
float coverage(float inside, float width) {
    return clamp(min(inside + 0.5, width) - max(inside - 0.5, 0.0), 0.0, 1.0);
}

// The pixel step (one axis) closest to direction d.
ivec2 axis_step(vec2 d) {
    return abs(d.x) >= abs(d.y) ? ivec2(sign(d.x), 0) : ivec2(0, sign(d.y));
}

void main() {
    ivec2 p;
    if (!fullscreen_pixel(p)) return;
    ivec2 size = textureSize(u_color, 0);
    vec4 result = premultiplied(p);
    if (!u_enabled) {
        write_final(p, vec4(result.rgb, 1.0));
        return;
    }
    LineEdge e = line_edge_decode(texelFetch(u_edge, p, 0));
    float depth = texelFetch(u_depth, p, 0).r;
    // This pixel's own line: its share of the pixel; the rest is the neighbour across the rim.
    if (e.line) {
        float cover = coverage(e.dist, e.width);
        ivec2 beyond = clamp(p + axis_step(e.dir), ivec2(0), size - 1);
        // Only over what is behind: where the neighbour's surface is in front (a line close
        // behind this pushed-back halo rim, say), that neighbour does not take this line's
        // fringe either, and the edge stays as drawn, so the outline keeps its darkness.
        if (cover < 1.0 && dot(e.dir, e.dir) > 0.25 && texelFetch(u_depth, beyond, 0).r > depth)
            result = mix(premultiplied(beyond), result, cover);
    }
    // The fringes of lines in front whose rims lie within half a pixel of this pixel's centre.
    // Per axis both sides count (a pixel in a thin gap between two lines in front shows both);
    // of the two axes the one that covers more (a corner's two fringes overlap, so they are not added).
    float cover[4];
    for (int i = 0; i < 4; ++i) {
        ivec2 q = clamp(p + kNeighbours[i], ivec2(0), size - 1);
        LineEdge en = line_edge_decode(texelFetch(u_edge, q, 0));
        // Signed distance inside q's line at this pixel's centre: moving out along dir lowers it.
        float inside = en.dist - dot(en.dir, vec2(-kNeighbours[i]));
        // A centre inside q's line was rasterised by it (or by what is in front of it, or it is
        // the same line's halo pushed back): only centres outside its rims take a fringe.
        float c = en.line && (inside < 0.0 || inside > en.width) ? coverage(inside, en.width) : 0.0;
        // Only a line in front of this pixel's surface covers it.
        cover[i] = c > 0.0 && texelFetch(u_depth, q, 0).r < depth ? c : 0.0;
    }
    int axis = cover[0] + cover[1] >= cover[2] + cover[3] ? 0 : 2;
    float c0 = cover[axis], c1 = cover[axis + 1];
    float fringe = c0 + c1;
    if (fringe > 1.0) {
        c0 /= fringe;
        c1 /= fringe;
        fringe = 1.0;
    }
    if (fringe > 0.0)
        result = result * (1.0 - fringe) + premultiplied(clamp(p + kNeighbours[axis], ivec2(0), size - 1)) * c0 +
                 premultiplied(clamp(p + kNeighbours[axis + 1], ivec2(0), size - 1)) * c1;
    if (u_alpha == 0) write_final(p, vec4(result.rgb, 1.0));
    else write_final(p, result.a > 0.0 ? vec4(result.rgb / result.a, result.a) : texelFetch(u_color, p, 0));
}
