#version 450 core
// resolve_list: per pixel, the list's fragments sorted by depth (ties by line id, so the result
// does not depend on the rasterisation order), composited front to back with early termination
// at alpha >= 0.99, over the background. The K nearest fragments are kept (a longer list drops
// its farthest ones and is counted). They are sorted in rounds of sort_block (oit_block_sort.glsl,
// as resolve_exact does): a pixel opaque within its first round never pays for an insertion sort
// of K; a list of faint fragments (variant 4) is better sorted in one round of K. With an AO map of an opaque core (variant2_oit_ao), AO is
// applied per fragment: only to fragments at the core's depth; faded fragments in front of the
// core and fragments behind it stay unoccluded.
#include "oit_list.glsl"
#ifdef VOLUME_AO  // every fragment shaded by its own AO from fill_list's records
#include "line_volume_ao.glsl"
uniform usamplerBuffer u_records;  // the pass's view of fill_list's records
#endif

// K, the nearest fragments kept (max_fragments), is compiled in: the arrays are K long, so a
// pixel pays for the lists the graph asked for, not for the largest one allowed.
#define K MAX_FRAGMENTS
#define OIT_BLOCK (K < SORT_BLOCK ? K : SORT_BLOCK)  // a round's block (sort_block), never beyond K

// The pins, by declaration (u_nodes is the pass's view of the `nodes` buffer):
layout(r32ui) uniform readonly uimage2D u_heads;
uniform usamplerBuffer u_nodes;
#include "oit_block_sort.glsl"
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
    float core = u_use_ao != 0 ? texelFetch(u_core, p, 0).w : 1.0;
    float ao = u_use_ao != 0 ? texelFetch(u_ao, p, 0).r : 1.0;
    vec3 lit = vec3(0.0), unlit = vec3(0.0);
    float alpha = 0.0;
    float front_ao = 1.0, front_alpha = 0.0, front_depth = 1.0;
    uint front_line = 0u, front_node = 0u;
    uint len = 0u;
    int composited = 0;  // at most K: the nearest K fragments, as one sort of K would keep
#ifdef VOLUME_AO
    // Each composited fragment's own AO, faded out with its colour hook's opacity (by default
    // the pathlet's end fade; faded ends stay clean): AO x fade + (1 - fade). The AO is evaluated
    // for the first VAO_LAYERS fragments; a fragment behind them takes the last one's AO.
    float own = 1.0;
#endif
    OitBlockAfter after = kOitBlockStart;
    for (;;) {
        uint walked;
        bool cut;
        int n = oit_sort_block(i, after, 0x1000000u, walked, cut);  // the bound only guards a corrupt list
        if (!after.any) {  // the first round: the list's length and its nearest fragment
            len = walked;
            front_alpha = unpackUnorm4x8(oit_block_col[0]).a;
            front_depth = oit_block_dep[0];
            front_line = oit_block_lid[0];
            front_node = oit_block_idx[0];
        }
        for (int k = 0; k < n && alpha < 0.99 && composited < K; ++k, ++composited) {
            vec4 c = unpackUnorm4x8(oit_block_col[k]);
            float w = (1.0 - alpha) * c.a;
#ifdef VOLUME_AO
            uvec4 record = texelFetch(u_records, int(oit_block_idx[k]));
            if (composited < VAO_LAYERS) own = line_volume_ao_unpacked(gl_FragCoord.xy, oit_block_dep[k], record);
            if (composited == 0) front_ao = own;
            float occlusion = mix(1.0, own, unpackHalf2x16(record.z).y);
#else
            float occlusion = abs(oit_block_dep[k] - core) <= u_ao_tolerance ? ao : 1.0;
#endif
            lit += w * c.rgb * occlusion;
            unlit += w * c.rgb;
            alpha += w;
        }
        if (alpha >= 0.99 || composited >= K || n < OIT_BLOCK || cut) break;
        after = oit_block_last();
    }
    // A plain read first: the peak only grows, so most pixels need no (contended) atomic.
    if (len > peak_nodes) atomicMax(peak_nodes, len);
    if (len > uint(K)) atomicAdd(truncated_pixels, 1u);
    // Alpha 1 wherever a fragment landed: bilateral (variant2_oit) treats it as geometry.
    float covered = 1.0;  // the list has a fragment
    o_color = vec4(lit + (1.0 - alpha) * u_background, covered);
#ifdef UNLIT_LOCATION
    o_unlit = vec4(unlit + (1.0 - alpha) * u_background, covered);
#endif
#ifdef FRONT_ALPHA_LOCATION
    o_front_alpha = front_alpha;
#endif
#ifdef FRONT_LOCATION
    uvec4 fr = texelFetch(u_records, int(front_node));
    o_front_normal_depth = vec4(vao_unocta(unpackSnorm2x16(fr.x)), front_depth);
    o_front_line_id = int(front_line);
    o_front_ao = front_ao;
#endif
}
