// The line kit's GLSL, shared by every stage that draws pathlet quads. A stage file defines
// one of LINE_STAGE_VERTEX, LINE_STAGE_GEOMETRY or LINE_STAGE_FRAGMENT before including this
// and gets that stage's interface and helpers. The uniform block and the per-pathlet buffer
// are filled by the kit's C++ side (pathlet/lines.hpp, lines::Drawer); their units and binding
// points are the engine's. Hooks: line_hooks.glsl.
#ifndef PATHLET_LINE_COMMON_GLSL
#define PATHLET_LINE_COMMON_GLSL

// LinePoint and the kit's uniform block:
#include "line_hooks.glsl"

vec3 line_safe_normalize(vec3 v, vec3 fallback) {
    float l2 = dot(v, v);  // one inverse square root instead of a square root and three divisions
    return l2 > 1e-24 ? v * inversesqrt(l2) : fallback;
}

// A view-space point in data coordinates (the view matrix is a rotation and a translation).
vec3 line_data_position(vec3 pos_view) { return transpose(mat3(u_view)) * (pos_view - u_view[3].xyz); }

// Members of the stage interfaces (a block name must match across stages; members too).
// position and tangent are in view space; arc is the arc length from the line's first point.
// point: the data point's index (gl_VertexID), so the GS knows how many data segments a
// segment after the level of detail stands for.
#define LINE_VERTEX_MEMBERS vec3 position; float time; float speed; float arc; vec3 tangent; flat int line_id; \
    flat int point;
// pos_view: point on the flat quad; side: unit vector across it (s = +1 side); s: -1..1
// across the width; half_width: the hooked half width here; age, arc_head, arc_tail, arc: LinePoint.
#define LINE_FRAGMENT_MEMBERS vec3 pos_view; vec3 side; vec3 tangent; float s; float speed; float time; \
    float age; float arc_head; float arc_tail; float arc; float half_width; flat int line_id;

#ifdef LINE_STAGE_VERTEX
#include "scene_points.glsl"
layout(location = 0) in float a_time;  // GpuScene::line_vao()
layout(location = 1) in int a_line_id;
layout(location = 2) in float a_speed;  // times u_scene_point_scale.x
layout(location = 3) in float a_arc;    // times u_scene_point_scale.y
out LineVertex { LINE_VERTEX_MEMBERS } v_out;

// View-space point and tangent, once per point (a point is shared by two segments, and
// llvmpipe runs the GS single-threaded, so per-point work belongs here). The position is
// fetched (gl_VertexID is the point's index in every kit draw), and the tangent is the central
// difference of the neighbours on the same line (one-sided at its ends), as the CPU once stored it.
void line_vertex() {
    const int i = gl_VertexID;
    const int prev = max(i - 1, 0), next = min(i + 1, scene_point_count() - 1);
    const int a = scene_point_line(prev) == a_line_id ? prev : i;
    const int b = scene_point_line(next) == a_line_id ? next : i;
    v_out.position = (u_view * vec4(scene_point_position(i), 1.0)).xyz;
    v_out.time = a_time;
    v_out.speed = a_speed * u_scene_point_scale.x;
    v_out.arc = a_arc * u_scene_point_scale.y;
    v_out.tangent = mat3(u_view) * line_safe_normalize(scene_point_position(b) - scene_point_position(a), vec3(1, 0, 0));
    v_out.line_id = a_line_id;
    v_out.point = i;
}
#endif

#ifdef LINE_STAGE_GEOMETRY
in LineVertex { LINE_VERTEX_MEMBERS } v_in[];
out LineFragment { LINE_FRAGMENT_MEMBERS } g_out;

// Per line, this frame (lines::Drawer): arc length at the pathlet's head and tail, and the
// times that age 0 and age 1 stand for. A buffer texture, not a storage block: GL 4.5 guarantees
// geometry shaders no storage blocks at all (GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS may be 0).
uniform samplerBuffer u_line_pathlets;

// The hook's view of a point at view-space position `pos_view`, data time `time` and arc length
// `arc` on line `id`.
LinePoint line_point(vec3 pos_view, float time, float arc, float speed, int id) {
    vec4 pl = texelFetch(u_line_pathlets, id);
    LinePoint p;
    p.time = time;
    p.age = clamp((pl.z - time) / max(pl.z - pl.w, 1e-9), 0.0, 1.0);
    p.arc_from_head = max(pl.x - arc, 0.0);
    p.arc_from_tail = max(arc - pl.y, 0.0);
    p.speed = speed;
    p.line_id = id;
    p.arc = arc;
    p.position = line_data_position(pos_view);
    return p;
}
#endif

#ifdef LINE_STAGE_FRAGMENT
#include "colormap.glsl"

in LineFragment { LINE_FRAGMENT_MEMBERS } g_in;
// Per line, its bundle (GpuScene::line_bundles_texture): what colormap=bundle colours by.
uniform usamplerBuffer u_line_bundles;

struct LineFrag {
    vec3 color;       // colour-mapped speed, before hooks, halos and lighting
    vec3 normal;      // view-space unit normal of the fake tube
    vec3 tangent;     // view-space unit tangent
    vec3 to_viewer;   // view-space unit vector from the fragment to the eye
    float eye_depth;  // distance along -z to the tube surface (world units)
    float depth01;    // linear depth over [near, far], halo push-back included, in [0,1]
    float halo;       // 0 outside the halo band, then 0..1 from its inner edge to the rim
    bool in_halo;
    float halo_band;  // width of the halo band in units of s (0 = no halo)
    float inv_halo_band;  // 1 / halo_band (0 when there is no halo)
    float abs_s;      // |s|: 0 on the centre line, 1 at the rim
    float s_per_px;   // change of s over one pixel across the line
    float rim_px;     // distance from the pixel centre to the nearer rim, in pixels (>= 0)
    vec2 rim_dir;     // unit screen direction out of the quad through the nearer rim
    float cap_px;     // distance from the pixel centre to the nearer end of the pathlet, in pixels
    vec2 cap_dir;     // unit screen direction out through that end (head or tail)
    LinePoint point;  // what the hooks see (time, age, arc lengths, speed, line id)
};

// Written for llvmpipe, where every division and square root is paid per fragment and a
// G-buffer fragment is drawn ~26 times per covered pixel: reciprocals are taken once and the
// normal needs two inverse square roots (side and v are unit and perpendicular, so the normal
// is unit without a third).
LineFrag line_fragment() {
    LineFrag f;
    // s runs linearly across the quad, so its screen gradient gives the rim in pixels (before
    // any discard: derivatives need the whole 2x2 quad).
    vec2 ds = vec2(dFdx(g_in.s), dFdy(g_in.s));
    float inv_ds = inversesqrt(max(dot(ds, ds), 1e-12));  // pixels per unit of s
    float s = clamp(g_in.s, -1.0, 1.0);
    f.abs_s = abs(s);
    f.s_per_px = 1.0 / inv_ds;  // change of s per pixel
    f.rim_px = (1.0 - f.abs_s) * inv_ds;
    f.rim_dir = (s < 0.0 ? -ds : ds) * inv_ds;
    // The ends are edges too: the arc length runs linearly along the quad, so its screen gradient
    // gives the distance to the head (arc_head = 0 there) or the tail in pixels, as s does across.
    vec2 da = vec2(dFdx(g_in.arc), dFdy(g_in.arc));
    float inv_da = inversesqrt(max(dot(da, da), 1e-24));  // pixels per unit of arc length
    bool head = g_in.arc_head < g_in.arc_tail;
    f.cap_px = max(head ? g_in.arc_head : g_in.arc_tail, 0.0) * inv_da;
    f.cap_dir = (head ? da : -da) * inv_da;
    float c = sqrt(max(1.0 - s * s, 0.0));
    // side is unit at both quad ends; between them its interpolation is a little shorter.
    float side2 = dot(g_in.side, g_in.side);
    vec3 side = side2 > 1e-24 ? g_in.side * inversesqrt(side2) : vec3(1.0, 0.0, 0.0);
    f.to_viewer = line_safe_normalize(-g_in.pos_view, vec3(0.0, 0.0, 1.0));
    // Circle cross-section: -side, through the view direction, to +side (not a linear blend).
    // v: the direction to the eye without its side component (the eye is at the origin).
    vec3 v = -g_in.pos_view + dot(g_in.pos_view, side) * side;
    float v2 = dot(v, v);
    v = v2 > 1e-24 ? v * inversesqrt(v2) : vec3(0.0, 0.0, 1.0);
    f.normal = s * side + c * v;
    f.tangent = line_safe_normalize(g_in.tangent, vec3(0.0, 1.0, 0.0));
    // Convex tube of the hooked radius: the surface bulges towards the viewer by r * sqrt(1 - s^2).
    float near = u_depth_range.x, far = u_depth_range.y;
    f.eye_depth = max(-g_in.pos_view.z - g_in.half_width * c, 1e-6);
    // The band is u_halo of the half width, but at least u_halo_min_px on screen (a 0.3 px
    // band only hits a pixel centre here and there: speckles) and at most half the half width.
    float band = u_halo > 0.0 ? clamp(max(u_halo, u_halo_min_px * f.s_per_px), u_halo, max(u_halo, 0.5)) : 0.0;
    f.halo_band = band;
    f.inv_halo_band = band > 0.0 ? 1.0 / band : 0.0;
    float inner = 1.0 - band;
    f.in_halo = band > 0.0 && f.abs_s > inner;
    f.halo = f.in_halo ? clamp((f.abs_s - inner) * f.inv_halo_band, 0.0, 1.0) : 0.0;
    // Halos go back in proportion to their distance into the band: close lines merge, far ones gap.
    f.depth01 = clamp((f.eye_depth - near) / max(far - near, 1e-6) + u_halo_depth * f.halo, 0.0, 1.0);
    float span = max(u_speed_range.y - u_speed_range.x, 1e-12);
    // The view matrix is a rotation and a translation: its transpose takes the tangent back to data axes.
    f.color = colormap_is_direction(u_colormap) ? colormap_direction(transpose(mat3(u_view)) * f.tangent)
            : colormap_is_bundle(u_colormap)    ? colormap_bundle(texelFetch(u_line_bundles, g_in.line_id).r)
                                                : colormap(u_colormap, (g_in.speed - u_speed_range.x) / span);
    f.point.time = g_in.time;
    f.point.age = clamp(g_in.age, 0.0, 1.0);
    f.point.arc_from_head = max(g_in.arc_head, 0.0);
    f.point.arc_from_tail = max(g_in.arc_tail, 0.0);
    f.point.speed = g_in.speed;
    f.point.line_id = g_in.line_id;
    f.point.arc = g_in.arc;
    f.point.position = line_data_position(g_in.pos_view);
    return f;
}

// The halo is a gradient from half-way to the full halo colour at the rim, so its start
// still marks the line's edge (the study: halos read by the start and end of the gradient).
// The tint is averaged over the pixel's footprint across the line (a box filter, exact for
// the piecewise-linear profile): a line one or two pixels wide gets its halo as an even
// darkening instead of dark pixels here and there.
float line_halo_integral(float x, float inner, float inv_band) {  // of the tint weight over |s| in [0, x]
    float d = clamp(x, inner, 1.0) - inner;
    return d * (0.5 + 0.25 * d * inv_band);
}
vec3 line_halo_tint(vec3 color, LineFrag f) {
    if (f.halo_band <= 0.0) return color;
    float inner = 1.0 - f.halo_band;
    float a = f.abs_s - 0.5 * f.s_per_px, b = min(f.abs_s + 0.5 * f.s_per_px, 1.0);
    float sum = line_halo_integral(b, inner, f.inv_halo_band) - line_halo_integral(max(a, 0.0), inner, f.inv_halo_band);
    if (a < 0.0) sum += line_halo_integral(-a, inner, f.inv_halo_band);  // the footprint reaches over the centre
    float w = sum / max(b - a, 1e-6);
    return mix(color, u_halo_color, clamp(w, 0.0, 1.0));
}

#include "line_edge_record.glsl"

// The edge record for edge_aa (the line passes' optional `edge` output; line_edge_record.glsl):
// the nearer rim, or near a pathlet's end the end (its far side is the pathlet's length).
vec4 line_edge(LineFrag f) {
    if (f.cap_px < f.rim_px) return line_edge_encode(f.cap_dir, f.cap_px, 4.0);
    return line_edge_encode(f.rim_dir, f.rim_px, 2.0 / f.s_per_px);
}

// The share of the pixel the quad covers, box-filtered across the rims (both: a line thinner than
// a pixel covers less) and the nearer end: what the transparency techniques multiply into the
// opacity, as edge_aa blends an opaque G-buffer.
float line_coverage(LineFrag f) {
    float width_px = 2.0 / f.s_per_px;
    float across = clamp(min(f.rim_px + 0.5, width_px) - max(f.rim_px - 0.5, 0.0), 0.0, 1.0);
    return across * clamp(0.5 + f.cap_px, 0.0, 1.0);
}

// Screen-door transparency for opaque targets: a fragment of opacity a survives where a 4x4
// ordered-dither threshold is below a (a = 1 always survives, a = 0 never).
float line_screen_door_threshold(vec2 frag_coord) {
    const float bayer[16] = float[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
    ivec2 q = ivec2(frag_coord) & 3;
    return (bayer[q.y * 4 + q.x] + 0.5) / 16.0;
}

// Window-space depth of linear depth d01, so the z-buffer sees tubes and pushed-back halos.
float line_window_depth(float d01) {
    float z = mix(u_depth_range.x, u_depth_range.y, d01);  // distance along -z
    float ndc = (u_proj[2][2] * -z + u_proj[3][2]) / z;
    return clamp(0.5 * ndc + 0.5, 0.0, 1.0);
}
#endif

#endif
