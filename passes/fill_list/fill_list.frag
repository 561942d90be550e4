#version 450 core
// fill_list's fragment stage: every fragment of a pathlet quad becomes a node of its pixel's
// linked list (take a node index from the counter, swap it into the head, link
// the old head), with its colour (speed map, colour hook, halo), the opacity of its colour hook
// (by default the kit's end fade, fade_opacity.frag) times its edge coverage, its linear depth
// and its line id; optionally a second record per node with its normal, tangent, axis and the
// hook's opacity, from which resolve_list shades every fragment by its own volume AO; and
// optionally variant 2's opaque G-buffer of the same fragments (line_gbuffer_out.glsl).
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_list.glsl"
#include "oit_fragment.glsl"
#ifdef WRITE_GBUFFER
#include "line_gbuffer_out.glsl"
#endif
#ifdef WRITE_RECORDS  // per node, what the kit's volume AO needs (resolve_list shades with it)
#include "line_volume_ao.glsl"
layout(rgba32ui) uniform writeonly uimageBuffer u_records;  // the pass's view of `records`
#endif

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(r32ui) uniform coherent uimage2D u_heads;            // the pin, by declaration
layout(rgba32ui) uniform writeonly uimageBuffer u_nodes;    // the pass's view of the `nodes` buffer
layout(std430, binding = COUNTER_BINDING) buffer OitCounter { uint oit_count; };  // the pin `counter`
uniform int u_capacity;  // nodes that fit; beyond it fragments are only counted

void main() {
    LineFrag f = line_fragment();
    vec4 c = line_color_hook(vec4(f.color, 1.0), f.point);
#ifdef WRITE_GBUFFER
    // Every fragment, opaque, as the gbuffer pass writes it. The depth test runs after this
    // shader (it writes gl_FragDepth), so a fragment the G-buffer hides still becomes a node.
    line_gbuffer_write(f, c.rgb);
#endif
    vec4 frag = oit_fragment_rgba(f, c);  // halo tint, and the opacity times the edge coverage
    float a = frag.a;
#ifdef WRITE_GBUFFER
    if (!oit_fragment_visible(a)) return;  // invisible: no node (its G-buffer values stay)
#else
    if (!oit_fragment_visible(a)) discard;  // invisible: no node
#endif
    uint i = atomicAdd(oit_count, 1u);
    if (i >= uint(u_capacity)) return;  // overflow: counted, fill_list re-renders the frame with more room
    uint next = imageAtomicExchange(u_heads, ivec2(gl_FragCoord.xy), i);
    imageStore(u_nodes, int(i), oit_pack(frag, f.depth01, next, f.point.line_id));
#ifdef WRITE_RECORDS
    imageStore(u_records, int(i), line_volume_ao_pack(f.normal, f.tangent, line_volume_ao_w(f), c.a));
#endif
}
