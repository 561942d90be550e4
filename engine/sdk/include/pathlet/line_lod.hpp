// Screen-space level of detail for pathlines. At the default framing a study-scale data set
// puts several segments on one pixel; drawing them costs vertex, geometry and setup work for
// nothing. Once at load, every point gets the tolerance (world units) up to which a
// Douglas-Peucker simplification of its line keeps it; per frame, a line's points whose
// tolerance exceeds `lod px` worth of world units at the line's distance are drawn.
//
// The error is the time-synchronised distance (the point against the position the simplified
// segment reaches at the point's time), so the time-window clip of the line kit, which
// interpolates in time, moves by no more than the tolerance either. Speed, which colours the
// lines, is kept within kSpeedTolerance of the colour range regardless of zoom.
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/scene.hpp>

#include <cstdint>
#include <vector>

namespace pathlet {

class LineLod {
public:
    // Relative speed error (of the colour range) a dropped point may have at any zoom.
    static constexpr float kSpeedTolerance = 0.004f;

    // speed_range: the speed span the colour map covers (for the speed criterion).
    void build(const Pathlines& lines, float speed_range);
    bool empty() const { return keep_.empty(); }

    // What to draw this frame: per drawn line the point indices kept, as strips for
    // glMultiDrawElements into one index buffer.
    struct Strips {
        std::vector<GLuint> index;
        std::vector<GLsizei> count;
        std::vector<const void*> offset;  // byte offsets into the index buffer
        size_t segments = 0;
    };
    // For each range [first[i], first[i] + count[i]) of line line[i]: the kept points, widened
    // to the nearest kept point before and after the range so the kit's time clip still finds
    // the window's ends. world_per_px(d) = scale * (perspective ? d : 1) with d the distance
    // from `eye` to the line's bounding box; lod_px: the tolerance in pixels.
    // max_skip: no drawn segment stands for more data segments than this (a width hook's
    // geometry shader splits a segment back into that many pieces, see line_quad.geom): every
    // max_skip-th point of a line, counted from its first, is kept. A per-point rule, so any
    // part of a line selects what the whole line would (the kit's GPU culling draws chunks).
    void select(const std::vector<GLint>& first, const std::vector<GLsizei>& count, const std::vector<uint32_t>& line,
                glm::vec3 eye, float scale, bool perspective, float lod_px, Strips& out,
                uint32_t max_skip = UINT32_MAX) const;
    // The tolerance of line `line` in world units this frame (select()'s rule): points whose
    // tolerance exceeds it are kept. Finite and >= 0.
    float tolerance(uint32_t line, glm::vec3 eye, float scale, bool perspective, float lod_px) const;
    // Per point, the tolerance below which it is kept (what tolerance() is compared with).
    const std::vector<float>& keep() const { return keep_; }

private:
    // Per point: the simplification tolerance (world units) below which the point is kept;
    // +inf at line ends and where dropping the point would change its colour.
    std::vector<float> keep_;
    std::vector<Bounds> line_box_;  // per line
    std::vector<uint32_t> line_first_;  // per line, its first point
};

}  // namespace pathlet
