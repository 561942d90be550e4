// The scene's line points on the GPU (pathlet/gpu_scene.hpp; GpuScene::bind_points sets all of
// this): per point its position in the lines' bounding box and its arc length, quantised to 16
// bits each or as floats (GpuScene::PointLayout), in one buffer; its time, line id and speed in
// another (the line VAO's attributes). Positions are decoded here only.
#ifndef PATHLET_SCENE_POINTS_GLSL
#define PATHLET_SCENE_POINTS_GLSL

uniform samplerBuffer u_scene_points;      // x, y, z, arc in 0..1 of the box (RGBA16) or as data (RGBA32F)
uniform samplerBuffer u_scene_point_data;  // time, line id (int bits), speed (RGB32F)
uniform vec4 u_scene_points_origin;        // the box's corner, 0 (0 for floats)
uniform vec4 u_scene_points_extent;        // its sides and the longest arc length (1 for floats)
uniform int u_scene_points_quantised;      // 1: 16 bits each, 0: floats (storage-buffer reads)

vec3 scene_point_decode(vec3 stored) { return u_scene_points_origin.xyz + stored * u_scene_points_extent.xyz; }
// Position (xyz) and arc length (w) of point i.
vec4 scene_point(int i) { return u_scene_points_origin + texelFetch(u_scene_points, i) * u_scene_points_extent; }
vec3 scene_point_position(int i) { return scene_point(i).xyz; }
int scene_point_count() { return textureSize(u_scene_points); }
float scene_point_time(int i) { return texelFetch(u_scene_point_data, i).x; }
int scene_point_line(int i) { return floatBitsToInt(texelFetch(u_scene_point_data, i).y); }
// The positions buffer read as a storage block of uints `words` (2 a point quantised, 4 floats).
#define SCENE_POINT_FROM_WORDS(words, i)                                                              \
    scene_point_decode(u_scene_points_quantised != 0                                                  \
        ? vec3(unpackUnorm2x16(words[2u * (i)]), unpackUnorm2x16(words[2u * (i) + 1u]).x)             \
        : uintBitsToFloat(uvec3(words[4u * (i)], words[4u * (i) + 1u], words[4u * (i) + 2u])))

#endif
