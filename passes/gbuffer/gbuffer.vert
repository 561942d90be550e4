#version 450 core
// Line points pass straight through to shaders/line_quad.geom (see line_common.glsl).
#define LINE_STAGE_VERTEX
#include "line_common.glsl"
void main() { line_vertex(); }
