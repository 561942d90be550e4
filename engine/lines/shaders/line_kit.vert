#version 450 core
// The line kit's vertex stage: line points pass to shaders/line_quad.geom (see line_common.glsl).
#define LINE_STAGE_VERTEX
#include "line_common.glsl"
void main() { line_vertex(); }
