// The exact references' rule for fragments at one depth (resolve_exact and depth_peel follow it,
// so they agree on every fragment): the fragments of a pixel with bitwise the same depth have no
// order, whatever their lines, so they are one layer, composited together. Like absorbing media
// mixed in one slab, their absorbances w = -ln(1 - alpha) add up and the layer's colour is their
// absorbance-weighted mean:
//   layer opacity 1 - exp(-sum w),   layer colour sum(w c) / sum(w).
// A lone fragment comes out as itself; N copies of one fragment as that fragment composited N
// times; and no order (line id, colour, raster order) decides anything. Ties are common where
// the linear depth is clamped: halos pushed past the far plane (1.0), tube bulges in front of the
// near plane (0.0).
#ifndef PATHLET_OIT_DEPTH_GROUP_GLSL
#define PATHLET_OIT_DEPTH_GROUP_GLSL

// An opaque fragment's light left: its absorbance stays finite (ln 2^20 = 13.9), and what it lets
// through (1e-6) is below every transmittance a reference stops at.
const float kOitOpaqueTransmittance = 1.0 / 1048576.0;
// Every stored fragment has some absorbance, so a layer is never empty: one whose opacity
// rounded to 0 of 255 still counts (as nothing to see) and is peeled once, not again and again.
const float kOitLeastAbsorbance = 1e-12;

// What a fragment adds to its depth's layer: (w c.rgb, w). `rgba` as the lists store it (8 bits).
vec4 oit_depth_group_term(vec4 rgba) {
    float w = max(-log(max(1.0 - rgba.a, kOitOpaqueTransmittance)), kOitLeastAbsorbance);
    return vec4(w * rgba.rgb, w);
}

// Composites a layer (the sum of its fragments' terms; w = 0: none) under what is there, front
// to back: `rgb` the colour so far (premultiplied), `t` the transmittance left.
void oit_depth_group_composite(inout vec3 rgb, inout float t, vec4 group) {
    if (group.a <= 0.0) return;
    float through = exp(-group.a);
    rgb += t * (1.0 - through) / group.a * group.rgb;
    t *= through;
}

// A layer built a fragment at a time (resolve_exact): empty (all zero), one fragment kept as it
// is (its opacity with the sign bit set, so an opacity of 0 is told from an empty layer), or the
// sum of the terms of two or more. A lone fragment, most layers, then costs no logarithm or
// exponential and is composited as itself (the formula above gives it up to float rounding).
bool oit_layer_empty(vec4 layer) { return floatBitsToUint(layer.a) == 0u; }
bool oit_layer_is_one(vec4 layer) { return (floatBitsToUint(layer.a) >> 31) != 0u; }
vec4 oit_layer_add(vec4 layer, vec4 rgba) {
    if (oit_layer_empty(layer)) return vec4(rgba.rgb, uintBitsToFloat(floatBitsToUint(rgba.a) | 0x80000000u));
    if (oit_layer_is_one(layer)) layer = oit_depth_group_term(vec4(layer.rgb, abs(layer.a)));
    return layer + oit_depth_group_term(rgba);
}
void oit_layer_composite(inout vec3 rgb, inout float t, vec4 layer) {
    if (!oit_layer_is_one(layer)) {
        oit_depth_group_composite(rgb, t, layer);
        return;
    }
    float a = abs(layer.a);
    rgb += t * a * layer.rgb;
    t *= 1.0 - a;
}

// A colour as the lists' nodes keep it (packUnorm4x8 of the clamped colour), for a technique
// that composites without storing it (depth peeling).
vec4 oit_list_stored(vec4 rgba) { return unpackUnorm4x8(packUnorm4x8(clamp(rgba, 0.0, 1.0))); }

#endif
