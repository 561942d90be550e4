// A fullscreen pass's shader, written once for both ways it runs (PassContext::fullscreen_program):
// the fragment stage behind fullscreen.vert, or a compute shader (FULLSCREEN_COMPUTE defined)
// with one invocation per pixel of the rectangle PassContext::dispatch_fullscreen covers.
//
//   void main() {
//       ivec2 p;
//       if (!fullscreen_pixel(p)) return;  // compute: past the rectangle, or background
//       ...                                // then write the output: `out` or imageStore
//
// Outputs differ by stage: a fragment output, or the image u_<pin> (layout(format) writeonly).
#ifdef FULLSCREEN_COMPUTE
// 8x8: the work group the H200 measurements used (../shared/reference/gpu-measurements.md).
layout(local_size_x = 8, local_size_y = 8) in;
uniform ivec4 u_fullscreen_rect;        // x0, y0, x1, y1 of the pixels to shade (end exclusive)
uniform bool u_fullscreen_on_geometry;  // only where u_fullscreen_depth < 1 (the G-buffer depth)
uniform sampler2D u_fullscreen_depth;

bool fullscreen_pixel(out ivec2 p) {
    p = u_fullscreen_rect.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, u_fullscreen_rect.zw))) return false;
    // The fragment version's GREATER depth test of the far plane against the G-buffer depth.
    return !u_fullscreen_on_geometry || texelFetch(u_fullscreen_depth, p, 0).r < 1.0;
}
#else
bool fullscreen_pixel(out ivec2 p) {
    p = ivec2(gl_FragCoord.xy);
    return true;
}
#endif
