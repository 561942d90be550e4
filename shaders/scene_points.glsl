// The scene's line points on the GPU (pathlet/gpu_scene.hpp; GpuScene::bind_points sets all of
// this): per point its position, quantised to 21 bits an axis in the lines' bounding box or as
// floats (GpuScene::PointLayout), in one buffer; its time, line id, speed and arc length in
// another (the line VAO's attributes). Positions are decoded here only.
#ifndef PATHLET_SCENE_POINTS_GLSL
#define PATHLET_SCENE_POINTS_GLSL

uniform usamplerBuffer u_scene_points;     // quantised: 2 words (RG32UI); exact: the floats' bits (RGB32UI)
uniform samplerBuffer u_scene_point_data;  // time, line id (int bits), ... (RGB32F or RGBA32F)
uniform vec3 u_scene_points_origin;        // the box's corner (0 for floats)
uniform vec3 u_scene_points_step;          // a code's step an axis (1 for floats)
uniform int u_scene_points_quantised;      // 1: 21 bits an axis, 0: floats
uniform vec2 u_scene_point_scale;          // the attributes' speed and arc: stored value times these

// x, y, z from a point's words (w.z unused when quantised).
vec3 scene_point_decode(uvec3 w) {
    const uint m = 0x1FFFFFu;
    vec3 stored = u_scene_points_quantised != 0
        ? vec3(uvec3(w.x & m, (w.x >> 21) | ((w.y & 0x3FFu) << 11), (w.y >> 10) & m))
        : uintBitsToFloat(w);
    return u_scene_points_origin + stored * u_scene_points_step;
}
vec3 scene_point_position(int i) { return scene_point_decode(texelFetch(u_scene_points, i).xyz); }
int scene_point_count() { return textureSize(u_scene_points); }
float scene_point_time(int i) { return texelFetch(u_scene_point_data, i).x; }
int scene_point_line(int i) { return floatBitsToInt(texelFetch(u_scene_point_data, i).y); }
// The positions buffer read as a storage block of uints `words` (2 a point quantised, 3 exact).
#define SCENE_POINT_FROM_WORDS(words, i)                                                       \
    (u_scene_points_quantised != 0                                                             \
        ? scene_point_decode(uvec3(words[2u * (i)], words[2u * (i) + 1u], 0u))                 \
        : scene_point_decode(uvec3(words[3u * (i)], words[3u * (i) + 1u], words[3u * (i) + 2u])))

#endif
