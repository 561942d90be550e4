#version 450 core
// mlab_blend's gather: per fragment, in raster order per pixel (ordered fragment shader
// interlock), into the pixel's front bucket (slot 0) or its depth-sorted nodes (slots 1..L).
// A slot is uvec2(packUnorm4x8(premultiplied rgb, alpha), floatBitsToUint(depth + 1)); all zero
// is empty (the buffer is cleared to 0 every frame; depth + 1 is never 0).
#extension GL_ARB_fragment_shader_interlock : require
layout(pixel_interlock_ordered) in;
#define LINE_STAGE_FRAGMENT
#include "line_common.glsl"
#include "oit_blend.glsl"

vec4 line_color_hook(vec4 rgba, LinePoint p);  // the pass's colour hook (color_hook)

layout(std430, binding = NODES_BINDING) coherent buffer MlabNodes { uvec2 mlab_slot[]; };
uniform sampler2D u_bucket;
uniform int u_width;

void main() {
    LineFrag f = line_fragment();
    vec4 c = oit_fragment_rgba(f, line_color_hook(vec4(f.color, 1.0), f.point));
    if (!oit_fragment_visible(c.a)) discard;
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 bucket = texelFetch(u_bucket, p, 0).rg;
    float d = f.depth01;
    if (d > bucket.g) discard;  // behind the pixel's nearest opaque fragment: hidden
    vec4 frag = vec4(oit_core_ao(c.rgb, f) * c.a, c.a);
    uint base = uint(p.y * u_width + p.x) * uint(MLAB_LAYERS + 1);
    beginInvocationInterlockARB();
    if (d < bucket.r) {
        // The front bucket: the faint fragments in front of the first substantial one, blended
        // in arrival order (MLABDB's approximation: their order is not kept).
        vec4 front = unpackUnorm4x8(mlab_slot[base].x);
        front = front + (1.0 - front.a) * frag;
        mlab_slot[base] = uvec2(packUnorm4x8(front), floatBitsToUint(1.0));
    } else {
        vec4 col[MLAB_LAYERS + 1];
        float dep[MLAB_LAYERS + 1];
        int n = 0;
        for (int k = 0; k < MLAB_LAYERS; ++k) {
            uvec2 s = mlab_slot[base + 1u + uint(k)];
            if (s == uvec2(0u)) break;
            col[n] = unpackUnorm4x8(s.x);
            dep[n] = uintBitsToFloat(s.y) - 1.0;
            ++n;
        }
        int j = n;  // insert sorted by depth
        for (; j > 0 && dep[j - 1] > d; --j) col[j] = col[j - 1], dep[j] = dep[j - 1];
        col[j] = frag;
        dep[j] = d;
        ++n;
        if (n > MLAB_LAYERS) {  // merge the last two: the farther behind the nearer
            col[MLAB_LAYERS - 1] = col[MLAB_LAYERS - 1] + (1.0 - col[MLAB_LAYERS - 1].a) * col[MLAB_LAYERS];
            n = MLAB_LAYERS;
        }
        for (int k = 0; k < n; ++k) mlab_slot[base + 1u + uint(k)] = uvec2(packUnorm4x8(col[k]), floatBitsToUint(dep[k] + 1.0));
    }
    endInvocationInterlockARB();
}
