// The line kit's G-buffer outputs (LineAO's inputs) and line_gbuffer_write(), which writes a
// fragment's colour, view-space tube normal + normalised linear depth, zoom (pixels per world
// unit) and the optional line id, rim and axis, and its depth. Each output exists when the pass
// binds its pin: WRITE_<PIN> and <PIN>_LOCATION come from lines::gbuffer_targets() (C++), so
// locations are never numbered here. Used by line_gbuffer.frag and by fill_list, which writes
// variant 2's opaque G-buffer in the same raster as its lists.
uniform float u_zoom_scale;  // (H/2) * P[1][1], set by lines::bind_gbuffer()

#ifdef WRITE_COLOR
layout(location = COLOR_LOCATION) out vec4 o_color;
#endif
#ifdef WRITE_NORMAL_DEPTH
layout(location = NORMAL_DEPTH_LOCATION) out vec4 o_normal_depth;
#endif
#ifdef WRITE_ZOOM
layout(location = ZOOM_LOCATION) out float o_zoom;
#endif
#ifdef WRITE_LINE_ID
layout(location = LINE_ID_LOCATION) out int o_line_id;
#endif
#ifdef WRITE_EDGE  // the rim for edge_aa (line_edge in line_common.glsl)
layout(location = EDGE_LOCATION) out vec4 o_edge;
#endif
#ifdef WRITE_TANGENT  // the tube's axis for volume_ao: tangent, eye depth to the axis' quad
layout(location = TANGENT_LOCATION) out vec4 o_tangent;
#endif

// An opaque fragment of colour `rgb` (before the halo) into the bound targets and the depth.
void line_gbuffer_write(LineFrag f, vec3 rgb) {
#ifdef WRITE_COLOR
    o_color = vec4(line_halo_tint(rgb, f), 1.0);
#endif
#ifdef WRITE_NORMAL_DEPTH
    o_normal_depth = vec4(f.normal, f.depth01);
#endif
#ifdef WRITE_ZOOM
    o_zoom = u_zoom_scale / f.eye_depth;
#endif
#ifdef WRITE_LINE_ID
    o_line_id = g_in.line_id;
#endif
#ifdef WRITE_EDGE
    o_edge = line_edge(f);
#endif
#ifdef WRITE_TANGENT
    o_tangent = vec4(f.tangent, -g_in.pos_view.z - mix(u_depth_range.x, u_depth_range.y, f.depth01));
#endif
    gl_FragDepth = line_window_depth(f.depth01);
}
