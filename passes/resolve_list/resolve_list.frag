#version 450 core
// resolve_list: per pixel, the list's fragments sorted by depth (ties by line id, so the result
// does not depend on the rasterisation order), composited front to back with early termination
// at alpha >= 0.99, over the background. The K nearest fragments are kept (a longer list drops
// its farthest ones and is counted). With an AO map of an opaque core (variant2_oit_ao), AO is
// applied per fragment: only to fragments at the core's depth; faded fragments in front of the
// core and fragments behind it stay unoccluded.
#include "oit_list.glsl"
#ifdef VOLUME_AO  // every fragment shaded by its own AO from fill_list's records (issue 25)
#include "line_volume_ao.glsl"
uniform usamplerBuffer u_records;  // the pass's view of fill_list's records
#endif

// K, the nearest fragments kept (max_fragments), is compiled in: the arrays are K long, so a
// pixel pays for the lists the graph asked for, not for the largest one allowed.
#define K MAX_FRAGMENTS

// The pins, by declaration (u_nodes is the pass's view of the `nodes` buffer):
layout(r32ui) uniform readonly uimage2D u_heads;
uniform usamplerBuffer u_nodes;
uniform sampler2D u_ao;    // smoothed AO of the core (when u_use_ao)
uniform sampler2D u_core;  // the core's normal + linear depth (w)
layout(std430, binding = STATS_BINDING) buffer OitResolveStats { uint peak_nodes; uint truncated_pixels; };
uniform int u_use_ao;
uniform float u_ao_tolerance;  // linear depth within which a fragment counts as the core surface
uniform vec3 u_background;

layout(location = 0) out vec4 o_color;
#ifdef UNLIT_LOCATION
layout(location = UNLIT_LOCATION) out vec4 o_unlit;
#endif
#ifdef FRONT_ALPHA_LOCATION
layout(location = FRONT_ALPHA_LOCATION) out float o_front_alpha;
#endif
#ifdef FRONT_LOCATION  // the nearest fragment as a G-buffer sees it, with its own AO (for quality)
layout(location = FRONT_LOCATION) out vec4 o_front_normal_depth;
layout(location = FRONT_LOCATION + 1) out int o_front_line_id;
layout(location = FRONT_LOCATION + 2) out float o_front_ao;
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    uint i = imageLoad(u_heads, p).r;
    if (i == OIT_END) {  // no fragment: the background (most pixels leave here)
        o_color = vec4(u_background, 0.0);
#ifdef UNLIT_LOCATION
        o_unlit = o_color;
#endif
#ifdef FRONT_ALPHA_LOCATION
        o_front_alpha = 0.0;
#endif
#ifdef FRONT_LOCATION
        o_front_normal_depth = vec4(0.0, 0.0, 0.0, 1.0);
        o_front_line_id = -1;
        o_front_ao = 1.0;
#endif
        return;
    }
    // Only the first n entries are read; setting the last keeps the compiler from warning (an
    // unrolled loop over all K cost 5 ms at 720p).
    float dep[K];
    uint col[K], lid[K];
    dep[K - 1] = 1.0, col[K - 1] = 0u, lid[K - 1] = 0u;
#ifdef VOLUME_AO
    uint rec[K];  // node index, for its record
    rec[K - 1] = 0u;
#endif
    int n = 0;
    uint len = 0u;
    while (i != OIT_END && len < 0x1000000u) {  // the bound only guards against a corrupt list
        uvec4 node = texelFetch(u_nodes, int(i));
        uint self = i;
        ++len;
        i = oit_next(node);
        float d = oit_depth(node);
        uint id = oit_line(node);
        if (n == K && !oit_nearer(d, id, node.x, dep[K - 1], lid[K - 1], col[K - 1])) continue;  // beyond the K kept
        int j = n < K ? n++ : K - 1;
        for (; j > 0 && oit_nearer(d, id, node.x, dep[j - 1], lid[j - 1], col[j - 1]); --j) {
            dep[j] = dep[j - 1];
            col[j] = col[j - 1];
            lid[j] = lid[j - 1];
#ifdef VOLUME_AO
            rec[j] = rec[j - 1];
#endif
        }
        dep[j] = d;
        col[j] = node.x;
        lid[j] = id;
#ifdef VOLUME_AO
        rec[j] = self;
#endif
    }
    // A plain read first: the peak only grows, so most pixels need no (contended) atomic.
    if (len > peak_nodes) atomicMax(peak_nodes, len);
    if (len > uint(K)) atomicAdd(truncated_pixels, 1u);
    float core = u_use_ao != 0 ? texelFetch(u_core, p, 0).w : 1.0;
    float ao = u_use_ao != 0 ? texelFetch(u_ao, p, 0).r : 1.0;
    vec3 lit = vec3(0.0), unlit = vec3(0.0);
    float alpha = 0.0;
    float front_ao = 1.0;
#ifdef VOLUME_AO
    // Each composited fragment's own AO, faded out with its colour hook's opacity (by default
    // the pathlet's end fade; faded ends stay clean): AO x fade + (1 - fade). The AO is evaluated for the first
    // VAO_LAYERS fragments, in a loop of its own (llvmpipe runs a loop as long as its longest
    // lane, and this one is expensive); a fragment behind them takes the last one's AO.
    float own[VAO_LAYERS];
    {
        float a = 0.0;
        for (int k = 0; k < VAO_LAYERS; ++k) own[k] = 1.0;
        for (int k = 0; k < min(n, VAO_LAYERS) && a < 0.99; ++k) {
            own[k] = line_volume_ao_unpacked(gl_FragCoord.xy, dep[k], texelFetch(u_records, int(rec[k])));
            a += (1.0 - a) * unpackUnorm4x8(col[k]).a;
        }
        front_ao = own[0];
    }
#endif
    for (int k = 0; k < n && alpha < 0.99; ++k) {
        vec4 c = unpackUnorm4x8(col[k]);
        float w = (1.0 - alpha) * c.a;
#ifdef VOLUME_AO
        float fade = unpackHalf2x16(texelFetch(u_records, int(rec[k])).z).y;
        float occlusion = mix(1.0, own[min(k, VAO_LAYERS - 1)], fade);
#else
        float occlusion = abs(dep[k] - core) <= u_ao_tolerance ? ao : 1.0;
#endif
        lit += w * c.rgb * occlusion;
        unlit += w * c.rgb;
        alpha += w;
    }
    // Alpha 1 wherever a fragment landed: bilateral (variant2_oit) treats it as geometry.
    float covered = n > 0 ? 1.0 : 0.0;
    o_color = vec4(lit + (1.0 - alpha) * u_background, covered);
#ifdef UNLIT_LOCATION
    o_unlit = vec4(unlit + (1.0 - alpha) * u_background, covered);
#endif
#ifdef FRONT_ALPHA_LOCATION
    o_front_alpha = n > 0 ? unpackUnorm4x8(col[0]).a : 0.0;
#endif
#ifdef FRONT_LOCATION
    uvec4 fr = texelFetch(u_records, int(rec[0]));
    o_front_normal_depth = vec4(vao_unocta(unpackSnorm2x16(fr.x)), dep[0]);
    o_front_line_id = int(lid[0]);
    o_front_ao = front_ao;
#endif
}
