// Object-space line AO from the line-density volume (line_density.glsl), for a point on a
// pathlet's tube: the share of cosine-weighted rays of length u_vao_reach that leave without
// meeting another tube, estimated from the density the rays pass through. Used per pixel by
// volume_ao and per fragment by any line pass (line_volume_ao_fragment below, e.g. fill_list's
// per-layer AO under OIT). The C++ side (pathlet::lines::VolumeAo) sets the uniforms and binds
// the volume; VAO_DIRECTIONS, VAO_STEPS and VAO_SECTION (the ray set) are compiled in.
//
// Per ray, step i of length ds meets an expected a_i = k w lambda_i ds tube crossings (lambda:
// pathlet length per volume; w: a tube's projected width per unit length) and lets 1 - min(1,
// a_i) of the light through: a crossing within one step is opaque for the share of rays that meet
// it, as a tube is, where exp(-a) would treat it as fog. The line's own tube is taken out: its
// share of the density near the point, a Gaussian tube around its axis of the splat kernel's
// width, is subtracted sample by sample.
//
// Two ray sets. hemisphere: a cosine-weighted Fibonacci set of directions, w = pi r / 2 (the mean
// over orientations, Cauchy's formula). section (VAO_SECTION): rays in the tube's cross-section
// only, and the rest of the hemisphere integrated analytically as if the neighbours ran parallel
// to the line, as they do in a bundle: a ray that leaves the section at elevation e towards the
// tangent crosses the same tubes as the section's ray in direction phi (w = 2r: a parallel
// tube's full width), only reaches R cos e into the section, and the cosine weight over (phi, e)
// is cos(phi) cos^2(e). So AO = 1/pi * sum_phi cos(phi) dphi * sum_i c_i T_i, with T_i the
// section ray's transmission at step i and c_i = integral of cos^2(e) over the elevations whose
// reach ends in step i (W(u) = asin(u) - u sqrt(1 - u^2), u = cos e). Eight section rays match
// 16 hemisphere rays against the ray-traced AO for the cost of 8.

#ifndef PATHLET_LINE_VOLUME_AO_GLSL
#define PATHLET_LINE_VOLUME_AO_GLSL

#include "line_density.glsl"

#ifndef VAO_DIRECTIONS
#define VAO_DIRECTIONS 8
#endif
#ifndef VAO_STEPS
#define VAO_STEPS 8
#endif

uniform float u_vao_reach;       // ray length, world units
uniform float u_vao_scale;       // k: calibration of the crossing rate (see the volume_ao README)
uniform float u_vao_radius;      // tube radius (half the line width), world units
uniform mat4 u_vao_inv_view;     // view -> world
uniform vec2 u_vao_depth_range;  // camera near, far
uniform vec4 u_vao_proj;         // P[0][0], P[1][1], P[3][0], P[3][1]
uniform int u_vao_perspective;
uniform vec2 u_vao_inv_size;     // 1 / output size in pixels

// The splat (trilinear deposit) seen through trilinear sampling is, on average over positions,
// a kernel of variance h^2 / 3 per axis; a straight line's share of the density at grid
// distance d (voxels) from its axis is then 3 / (2 pi) exp(-1.5 d^2) voxel lengths per voxel.
// The subtraction is widened to exp(-1.125 d^2): the kernel changes with where a line crosses
// the voxels and the G-buffer's depth is half floats, and the narrow one left an isolated line
// up to 6 % self-occlusion at the phantom's voxel size (1.4 radii).
const float kVaoOwnPeak = 0.4774648;
const float kVaoOwnFalloff = 1.125;

vec3 vao_normalize(vec3 v, vec3 fallback) {
    float l2 = dot(v, v);
    return l2 > 1e-24 ? v * inversesqrt(l2) : fallback;
}

// The own line's share of the density at grid point x, for a line through grid point qg along t.
float vao_own(vec3 x, vec3 qg, vec3 t) {
    vec3 rel = x - qg;
    float along = dot(rel, t);
    return kVaoOwnPeak * exp(-kVaoOwnFalloff * max(dot(rel, rel) - along * along, 0.0));
}

// Where a ray's samples lie within their steps, per direction: a golden-ratio sequence over the
// middle 70 % of the step, so that neighbouring directions sample at different distances.
// Midpoints on every ray put all samples on rings around the point, and a line crossing a ring
// changed every direction at once (flicker); offsets near 0 sampled the point itself, where the
// own tube's subtraction is least exact (an isolated line darkened by 5 % at the phantom's voxel).
float vao_sample_offset(int k) {
    return 0.15 + 0.7 * fract(0.5 + float(k) * 0.618034);
}

// The largest tilt of a section ray along its line, in lengths along the line per length in the
// section (see vao_open).
const float kVaoTilt = 0.7;

// A ray from grid point pg along d (not necessarily unit), in the density texture's coordinates:
// a sample s voxels along it is at start + dir s. own: the squared distance from the own line's
// axis (through qg along unit t) as a quadratic in s, (a, b, c) -> a + s (b + s c), times the
// falloff (the dot products per sample taken out of the loop).
struct VaoRay {
    vec3 start;
    vec3 dir;
    vec3 own;
};
VaoRay vao_ray(vec3 pg, vec3 d, vec3 qg, vec3 t) {
    vec3 e = pg - qg;
    float et = dot(e, t), dt = dot(d, t);
    VaoRay r;
    r.start = line_density_texcoord(pg);
    r.dir = d / vec3(density_dims.xyz);
    r.own = kVaoOwnFalloff * vec3(dot(e, e) - et * et, 2.0 * (dot(e, d) - et * dt), dot(d, d) - dt * dt);
    return r;
}

// The transmission of a ray, VAO_STEPS steps of ds voxels sampled at `offset` within each, `rate`
// crossings per unit of the texture's density per step; after each step into trans[i].
// The own share exp(-x), x = falloff d^2, is taken as (1 - x / 16)^16, which is zero from
// x = 16: a few multiplies a sample and no branch. Skipping it beyond the first voxels by a
// branch cost every sample the exp on llvmpipe (masked execution); (1 - x / 8)^8 was too narrow
// (an isolated line kept 2 % of itself).
void vao_march(VaoRay ray, float ds, float offset, float rate, out float trans[VAO_STEPS]) {
    const float own_peak = kVaoOwnPeak / kLineDensityUnit;
    float transmit = 1.0;
    for (int i = 0; i < VAO_STEPS; ++i) {
        float s = (float(i) + offset) * ds;
        float lambda = line_density_raw(ray.start + ray.dir * s);
        float own = max(1.0 - 0.0625 * (ray.own.x + s * (ray.own.y + s * ray.own.z)), 0.0);
        own *= own;
        own *= own;
        own *= own;
        lambda -= own_peak * own * own;
        transmit *= 1.0 - min(1.0, rate * max(lambda, 0.0));
        trans[i] = transmit;
    }
}

// The share of cosine-weighted rays that leave, from grid point pg on a tube with unit normal n,
// axis through qg along t, tx: t made perpendicular to n.
float vao_open(vec3 pg, vec3 n, vec3 qg, vec3 t, vec3 tx, float ds, float r_h) {
    float trans[VAO_STEPS];
    float open = 0.0;
    vec3 b = cross(n, tx);
#ifdef VAO_SECTION
    float reach[VAO_STEPS];  // c_i: the cosine weight of the elevations whose reach ends in step i
    for (int i = 0; i < VAO_STEPS; ++i) {
        float u0 = float(i) / float(VAO_STEPS), u1 = float(i + 1) / float(VAO_STEPS);
        reach[i] = (asin(u1) - u1 * sqrt(1.0 - u1 * u1)) - (asin(u0) - u0 * sqrt(1.0 - u0 * u0));
    }
    float rate = u_vao_scale * 2.0 * r_h * ds * kLineDensityUnit;
    for (int k = 0; k < VAO_DIRECTIONS; ++k) {
        // Cosine-weighted in the section: uniform in sin(phi), so every ray weighs the same and
        // the rays crowd where the weight is (they were spread evenly in phi, weighted by cos).
        float sin_phi = 2.0 * (float(k) + 0.5) / float(VAO_DIRECTIONS) - 1.0;
        vec3 d = sqrt(1.0 - sin_phi * sin_phi) * n + sin_phi * b;
        // Tilted along the line, by -kVaoTilt .. kVaoTilt per section length (s stays the
        // distance in the section). In a bundle of parallel lines the samples read the same; but
        // where a neighbour ends (a pathlet's head or tail moving by) the directions meet its end
        // at different distances along the line, so the AO ramps over frames as the ray-traced
        // AO does, where the section alone switched within a voxel (flicker).
        float tilt = kVaoTilt * ((mod(float(k) * 7.0, float(VAO_DIRECTIONS)) + 0.5) * (2.0 / float(VAO_DIRECTIONS)) - 1.0);
        vao_march(vao_ray(pg, d + tilt * t, qg, t), ds, vao_sample_offset(k), rate, trans);
        float before = 1.0;
        for (int i = 0; i < VAO_STEPS; ++i) {
            open += reach[i] * 0.5 * (before + trans[i]);  // the step's mean transmission
            before = trans[i];
        }
    }
    return open / (float(VAO_DIRECTIONS) * 1.5707963);  // the c_i add up to pi / 2
#else
    float rate = u_vao_scale * 1.5707963 * r_h * ds * kLineDensityUnit;
    for (int k = 0; k < VAO_DIRECTIONS; ++k) {
        // Cosine-weighted Fibonacci set: uniform in the projected disc, a golden angle apart.
        float rr = sqrt((float(k) + 0.5) / float(VAO_DIRECTIONS));
        float phi = float(k) * 2.3999632;
        vec3 d = rr * cos(phi) * tx + rr * sin(phi) * b + sqrt(1.0 - rr * rr) * n;
        vao_march(vao_ray(pg, d, qg, t), ds, vao_sample_offset(k), rate, trans);
        open += trans[VAO_STEPS - 1];
    }
    return open / float(VAO_DIRECTIONS);
#endif
}

// p: the point, n: its unit normal, q: a point on its own line's axis, t: the line's unit
// tangent; all in world space. Returns 1 (open) .. 0 (occluded).
float line_volume_ao_world(vec3 p, vec3 n, vec3 q, vec3 t) {
    float inv_h = 1.0 / density_origin.w;
    vec3 pg = line_density_grid(p), qg = line_density_grid(q);
    // Ray frame around the normal, turned with the line (stable as the line moves on screen).
    vec3 tx = vao_normalize(t - dot(t, n) * n, vao_normalize(cross(n, abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)), n));
    float r_h = u_vao_radius * inv_h;
    float open = vao_open(pg, n, qg, t, tx, u_vao_reach * inv_h / float(VAO_STEPS), r_h);
    // The point itself may lie inside another line's tube (pathlets that overlap, or a
    // neighbour's halo pushed back behind this line): then nothing is open. Its chance is the
    // other tubes' volume fraction there, pi r^2 lambda (Poisson). The own line is taken out 1.5
    // times here, where its share is largest and least certain: an isolated line must stay open.
    float others = max(line_density_at(pg) - 1.5 * vao_own(pg, qg, t), 0.0);
    return exp(-3.14159265 * r_h * r_h * others) * open;
}

// The same from view-space values (the G-buffer's and the kit's fragment space).
float line_volume_ao_view(vec3 p, vec3 n, vec3 q, vec3 t) {
    mat3 r = mat3(u_vao_inv_view);
    return line_volume_ao_world((u_vao_inv_view * vec4(p, 1.0)).xyz, normalize(r * n), (u_vao_inv_view * vec4(q, 1.0)).xyz,
                                normalize(r * t));
}

// ---- from what a G-buffer keeps ---------------------------------------------------------

// View-space point of the pixel at normalised device xy `ndc` and eye depth `eye` (along -z).
vec3 vao_view_point(vec2 ndc, float eye) {
    if (u_vao_perspective != 0) return vec3(ndc * eye / u_vao_proj.xy, -eye);
    return vec3((ndc - u_vao_proj.zw) / u_vao_proj.xy, -eye);
}

// The AO of the surface a pixel shows, where the ray-traced reference of `pathlet quality`
// places it: where the pixel's ray meets the line's round tube, with that tube's normal. From
// what the G-buffer keeps: the point at linear depth depth01 along the pixel's ray, the kit's
// view-space normal n, the view-space tangent t, and w, the eye depth from that point back to
// the quad through the axis. The kit's depth is not the tube's: it bulges towards the viewer
// by r sqrt(1 - s^2) along the view axis, where an inclined tube's surface lies nearer by
// 1 / sin(angle between the line and the ray), and halos are pushed back further; so the point
// is rebuilt from the quad and the axis.
struct VaoSurface {
    vec3 point;   // on the tube, view space
    vec3 normal;  // the tube's, unit
    vec3 axis;    // a point on the tube's axis
    vec3 tangent; // the axis' direction, unit
};
VaoSurface vao_surface(vec2 frag_coord, float depth01, vec3 n, vec3 t, float w) {
    vec2 ndc = frag_coord * u_vao_inv_size * 2.0 - 1.0;
    float eye = mix(u_vao_depth_range.x, u_vao_depth_range.y, depth01);
    vec3 quad = vao_view_point(ndc, eye + w);  // the pixel's point on the quad through the axis
    n = vao_normalize(n, vec3(0.0, 0.0, 1.0));
    VaoSurface v;
    v.tangent = vao_normalize(t, vec3(0.0, 1.0, 0.0));
    vec3 to_viewer = u_vao_perspective != 0 ? vao_normalize(-quad, vec3(0.0, 0.0, 1.0)) : vec3(0.0, 0.0, 1.0);
    // The quad's side as the kit's geometry stage builds it; n = s side + c v gives s.
    vec3 across = cross(v.tangent, to_viewer);
    vec3 side = vao_normalize(across, vec3(1.0, 0.0, 0.0));
    float s = clamp(dot(n, side), -1.0, 1.0);
    v.axis = quad - s * u_vao_radius * side;
    // Back along the ray to the tube: the ray crosses the tube's section at sin(angle) of its
    // speed (clamped: a line seen end-on keeps a finite depth).
    float sin_angle = max(length(across), 0.25);
    v.point = quad + (u_vao_radius * sqrt(1.0 - s * s) / sin_angle) * to_viewer;
    vec3 radial = v.point - v.axis;
    v.normal = vao_normalize(radial - dot(radial, v.tangent) * v.tangent, n);
    return v;
}

float line_volume_ao_gbuffer(vec2 frag_coord, float depth01, vec3 n, vec3 t, float w) {
    VaoSurface v = vao_surface(frag_coord, depth01, n, t, w);
    return line_volume_ao_view(v.point, v.normal, v.axis, v.tangent);
}

// Octahedral unit vectors in 32 bits (snorm 16 x 2): a record per OIT fragment.
vec2 vao_octa(vec3 v) {
    v /= abs(v.x) + abs(v.y) + abs(v.z);
    vec2 e = v.xy;
    if (v.z < 0.0) e = (1.0 - abs(e.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 vao_unocta(vec2 e) {
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
    return normalize(v);
}

// What line_volume_ao_gbuffer needs besides the pixel and the depth, packed: normal, tangent,
// w and a free value (fill_list keeps the end fade there).
uvec4 line_volume_ao_pack(vec3 n, vec3 t, float w, float extra) {
    return uvec4(packSnorm2x16(vao_octa(n)), packSnorm2x16(vao_octa(t)), packHalf2x16(vec2(w, extra)), 0u);
}
float line_volume_ao_unpacked(vec2 frag_coord, float depth01, uvec4 rec) {
    vec2 w = unpackHalf2x16(rec.z);
    return line_volume_ao_gbuffer(frag_coord, depth01, vao_unocta(unpackSnorm2x16(rec.x)), vao_unocta(unpackSnorm2x16(rec.y)),
                                  w.x);
}

#ifdef LINE_STAGE_FRAGMENT
// A kit fragment (include after line_common.glsl): w, the eye depth from its point (linear
// depth, the halo's push-back included) back to its quad.
float line_volume_ao_w(LineFrag f) {
    return -g_in.pos_view.z - mix(u_depth_range.x, u_depth_range.y, f.depth01);
}
// The fragment's own AO, exactly what volume_ao computes from a G-buffer of this fragment.
float line_volume_ao_fragment(LineFrag f) {
    return line_volume_ao_gbuffer(gl_FragCoord.xy, f.depth01, f.normal, f.tangent, line_volume_ao_w(f));
}
#endif

#endif
