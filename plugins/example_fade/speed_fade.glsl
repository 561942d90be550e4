// Speed-weighted fade: slow flow fades sooner, fast jets keep long tails. From its head a
// pathlet keeps full strength back to an age that grows with its speed, then fades out over
// `softness` of its length. One file for every line pipeline: as a colour hook it fades the
// opacity (fill_list: real transparency), as a width hook it tapers the width (the opaque
// G-buffer of variant 1: a round tube to the tip, no dithering). A hook is only its function:
// the kit puts the version line and its definitions (LinePoint, u_speed_range: line_hooks.glsl)
// before it.

uniform float u_keep_slow;  // @param 0.15 [0, 1] "age up to which the slowest flow keeps its full strength (0 = the head)"
uniform float u_keep_fast;  // @param 0.75 [0, 1] "age up to which the fastest flow keeps its full strength"
uniform float u_softness;   // @param 0.25 [0.01, 1] "length of the fade behind that, as a share of the pathlet"

// 1 near the head, 0 beyond keep + softness; speed measured on the colour map's range.
float speed_fade(LinePoint p) {
    float s = clamp((p.speed - u_speed_range.x) / max(u_speed_range.y - u_speed_range.x, 1e-6), 0.0, 1.0);
    float keep = mix(u_keep_slow, u_keep_fast, s);
    return 1.0 - smoothstep(keep, keep + u_softness, p.age);
}

vec4 line_color_hook(vec4 rgba, LinePoint p) { return vec4(rgba.rgb, rgba.a * speed_fade(p)); }
float line_width_hook(LinePoint p) { return speed_fade(p); }
