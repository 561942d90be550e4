// The line kit's uniform block: what every stage of a kit program (the kit's own and the
// hooks) sees of the current draw. Filled by lines::Drawer from one C++ struct whose layout is
// checked against this declaration for every program the kit makes; its binding point is the
// engine's (ShaderProgram::block_binding), so no number is written here.
#ifndef PATHLET_LINE_KIT_BLOCK_GLSL
#define PATHLET_LINE_KIT_BLOCK_GLSL

layout(std140) uniform LineKit {
    mat4 u_view;
    mat4 u_proj;
    vec2 u_window;           // [t0, t1] in seconds
    vec2 u_depth_range;      // camera near, far
    vec2 u_speed_range;      // speed mapped to colour 0 and 1
    int u_windowed;          // 0: draw lines whole
    float u_half_width;      // world units, half the quad width (halo included), before the width hook
    float u_max_width_hook;  // the width hook's result is clamped to [0, this] (GpuScene::kMaxWidthHook)
    float u_halo;            // fraction of the width that is halo (0 = none)
    float u_halo_min_px;     // the halo band is never thinner than this on screen (pixels)
    float u_halo_depth;      // push-back at the rim, normalised linear depth
    vec3 u_halo_color;
    int u_colormap;
    float u_typical_length;  // a typical pathlet's length (lines::typical_pathlet_length): arc-length measures
};

#endif
