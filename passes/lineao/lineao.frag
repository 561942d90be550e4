#version 450 core
// LineAO (Eichelbaum et al. 2013) as specified in shared/LINEAO.md. Loop bounds and every
// per-level constant are uniforms (computed on the CPU in lineao.cpp), so parameter changes
// need no recompile; the sample kernel is generated in the loop (level_samples). Uniforms named
// after a parameter (u_r0, u_strength, ...) and the samplers named after a pin are set by the
// SDK from the pass's declaration.
#include "fullscreen_pass.glsl"
#include "lineao_common.glsl"
#include "pow_whole.glsl"

#define MAX_LEVELS 8

#ifdef FULLSCREEN_COMPUTE
#ifdef LINEAO_HALF  // resolution = half: the term goes to the internal texture `half`
layout(r16f) writeonly uniform image2D u_half;
void write_ao(ivec2 p, float ao) { imageStore(u_half, p, vec4(ao)); }
#else
layout(r16f) writeonly uniform image2D u_ao;
void write_ao(ivec2 p, float ao) { imageStore(u_ao, p, vec4(ao)); }
#endif
#else
layout(location = 0) out float o_ao;
void write_ao(ivec2 p, float ao) { o_ao = ao; }
#endif
uniform sampler2D u_normal_depth;  // level-0 normal (xyz) + linear depth (w)
uniform sampler2D u_pyramid;       // mip l = level l (only read when u_from_pyramid)
uniform sampler2D u_zoom;          // px per world unit at the fragment

uniform int u_radii;                    // s_r
uniform int u_count[MAX_LEVELS];        // s_h / (l + 1)
uniform float u_growth[MAX_LEVELS];     // r_l = r0 + growth_l * line width on screen
uniform float u_delta[MAX_LEVELS];      // delta(l), already guarded > delta0
uniform vec2 u_level_dir[MAX_LEVELS];   // (cos, sin) of level l's starting angle in the Fibonacci spiral
uniform float u_r0;                     // px (times the pixel scale)
uniform float u_step_width;             // world units per radius step: the line width drawn
uniform float u_strength;
uniform float u_delta0;
uniform bool u_from_pyramid;            // use_pyramid and the pyramid is connected
uniform int u_max_lod;
uniform int u_lod_offset;               // log2 of the pixel scale: level l reads the mip of the same footprint
uniform bool u_occluder_light;
uniform vec3 u_light;                   // unit, view space
uniform float u_exponent;
uniform uint u_seed;
uniform float u_spec_cut;               // below this cosine, cos^exponent < 1e-4: skip the pow
uniform int u_resolution;               // 1 (half): this fragment stands for full-res pixel 2p

// The samples of level l: sum of g_depth * g_light and n_l. `pyramid` is a constant at each
// call, so each inlined copy has one texel fetch: llvmpipe evaluates both sides of a select,
// and a select between two fetches paid for both on every sample (LineAO 47 -> 40.5 ms at 720p).
void level_samples(const bool pyramid, int l, int lod, ivec2 lod_size, ivec2 size, vec2 frag, vec3 n, float d,
                   mat2 rot, float rnd_y, float radius, out float sum, out int used) {
    sum = 0.0;
    used = 0;  // n_l: samples on screen and on geometry
    // Level l's kernel, generated as it is used (a uniform array indexed by the loop counter is
    // a per-lane gather on llvmpipe: a fifth of the pass): sample i of n is the Fibonacci
    // hemisphere direction at height z = 1 - (i + 1/2)/n and angle i * golden + start, turned by
    // the pixel's rotation (one complex product per sample), with the van der Corput radial base.
    const vec2 golden = vec2(-0.7373688780783201, 0.6754902942615235);  // (cos, sin) of the golden angle
    vec2 dir = rot * u_level_dir[l];
    float inv_n = 1.0 / float(u_count[l]);
    for (int i = 0; i < u_count[l]; ++i, dir = vec2(dir.x * golden.x - dir.y * golden.y, dir.x * golden.y + dir.y * golden.x)) {
        float z = 1.0 - (float(i) + 0.5) * inv_n;
        vec3 w = vec3(sqrt(max(1.0 - z * z, 0.0)) * dir, z);
        w = dot(w, n) < 0.0 ? -w : w;  // into the hemisphere of n (side of the tube)
        float radial = float(bitfieldReverse(uint(i))) * 2.3283064365386963e-10;  // van der Corput
        float len = 0.25 + 0.75 * fract(radial + rnd_y);
        ivec2 q = ivec2(floor(frag + w.xy * (len * radius)));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 occ = pyramid ? texelFetch(u_pyramid, min(q >> lod, lod_size - 1), lod) : texelFetch(u_normal_depth, q, 0);
        if (!nd_is_geometry(occ)) continue;
        ++used;
        float dd = d - occ.w;       // > 0: the sample is in front of P
        if (dd <= u_delta0) continue;  // V = 1: not occluded
        float g_depth = 1.0 - smoothstep(u_delta0, u_delta[l], dd);
        // Light reflected by the occluder towards P (Blinn-Phong on the occluder's
        // normal, weighted by P's cosine to w); clamped so it never brightens.
        vec3 no = normalize(occ.xyz);
        float cos_p = max(dot(w, n), 0.0);
        vec3 h = u_light + w;  // zero when w points straight away from the light
        float hn = dot(h, h) > 1e-8 ? dot(normalize(h), no) : 0.0;
#ifdef LINEAO_EXPONENT  // a whole exponent (lineao.cpp): products instead of pow
        float spec = hn > u_spec_cut ? pow_whole(hn, LINEAO_EXPONENT) : 0.0;
#else
        float spec = hn > u_spec_cut ? pow(hn, u_exponent) : 0.0;
#endif
        float diff = u_occluder_light ? max(dot(no, u_light), 0.0) : 0.0;
        float g_light = 1.0 - min(cos_p * (spec + diff), 1.0);
        sum += g_depth * g_light;
    }
}

void main() {
    // Everything below is in full-resolution pixels; at half resolution a fragment computes the
    // term of the first pixel of its 2x2 block (lineao_upsample.frag fills in the others).
    ivec2 out_p;
    if (!fullscreen_pixel(out_p)) return;
    vec2 frag = vec2(u_resolution == 1 ? out_p * 2 : out_p) + 0.5;
    ivec2 p = ivec2(frag);
    vec4 nd = texelFetch(u_normal_depth, p, 0);
    if (!nd_is_geometry(nd)) {  // background: skipped, unoccluded
        write_ao(out_p, 1.0);
        return;
    }
    vec3 n = normalize(nd.xyz);
    float d = nd.w;
    ivec2 size = textureSize(u_normal_depth, 0);
    float width_px = texelFetch(u_zoom, p, 0).r * u_step_width;

    // Fixed per-pixel rotation about the view axis and radial offset: reproducible noise.
    vec2 rnd = lineao_rand2(lineao_hash3(uvec3(p, u_seed)));
    float ang = 6.28318530718 * rnd.x;
    mat2 rot = mat2(cos(ang), sin(ang), -sin(ang), cos(ang));

    ivec2 pyramid_size = textureSize(u_pyramid, 0);
    float line_ao = 0.0;
    for (int l = 0; l < u_radii; ++l) {
        float radius = u_r0 + u_growth[l] * width_px;
        // Where level l's samples come from, decided once per level (not per sample).
        bool from_pyramid = u_from_pyramid && l > 0;
        int lod = from_pyramid ? min(l + u_lod_offset, u_max_lod) : 0;
        // GL's mip size rule rather than textureSize(u_pyramid, lod): llvmpipe answers a size query
        // for the whole SIMD bundle with one lane's lod, and a lane that already returned
        // (background) made it level 0's size, so the clamp below let fetches fall off odd-sized
        // levels (found by the compute port's test at 333x217).
        ivec2 lod_size = from_pyramid ? max(pyramid_size >> lod, ivec2(1)) : size;
        float sum;
        int used;
        if (from_pyramid)
            level_samples(true, l, lod, lod_size, size, frag, n, d, rot, rnd.y, radius, sum, used);
        else
            level_samples(false, l, lod, lod_size, size, frag, n, d, rot, rnd.y, radius, sum, used);
        line_ao += used > 0 ? sum / float(used) : 0.0;  // empty level: 0, never NaN
    }
    write_ao(out_p, clamp(1.0 - u_strength / float(u_radii) * line_ao, 0.0, 1.0));
}
