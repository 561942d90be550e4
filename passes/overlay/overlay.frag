#version 450 core
// The overlay's three kinds of rectangle: text (a FreeType coverage bitmap in the colour),
// the colour bar (the line passes' colour map, top = fast), solid (the bar's frame) and a bundle's
// swatch (its colour in the bundle colour map).
#include "colormap.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_text;
uniform int u_mode;  // 0 text, 1 colour bar, 2 solid, 3 bundle swatch
uniform int u_bundle;  // mode 3: which bundle
uniform vec4 u_color;
uniform int u_colormap;  // the parameter, by declaration
void main() {
    if (u_mode == 0) o_color = vec4(u_color.rgb, u_color.a * texture(u_text, v_uv).r);
    else if (u_mode == 1) o_color = vec4(colormap(u_colormap, 1.0 - v_uv.y), 1.0);
    else if (u_mode == 3) o_color = vec4(colormap_bundle(uint(u_bundle)), 1.0);
    else o_color = u_color;
}
