// Every line split once, at load, into chunks of up to kSegments segments with a bounding box:
// the unit of the line kit's culling (lines::Drawer: frustum and two-phase occlusion culling).
// Consecutive chunks of a line share their end point, so drawing a chunk's points draws
// exactly its segments and the chunks of a line together draw the line.
#pragma once

#include <pathlet/scene.hpp>

#include <cstdint>
#include <vector>

namespace pathlet {

class LineChunks {
public:
    // Short chunks have tight boxes: on the study phantom with every line at 720p, 8 segments
    // leave 62k of 234k segments to draw after occlusion culling, 16 leave 78k, 32 leave 104k
    // (4 leave 53k, but the per-chunk work then costs more than it saves).
    static constexpr uint32_t kSegments = 8;

    struct Chunk {
        Bounds box;          // of the chunk's finite points (invalid when it has none)
        uint32_t first = 0;  // first point (index into the scene's points)
        uint32_t last = 0;   // last point; the next chunk of the line starts here
    };

    void build(const Pathlines& lines);
    const std::vector<Chunk>& chunks() const { return chunks_; }
    // The chunks of line `line`: [begin(line), end(line)).
    uint32_t begin(uint32_t line) const { return line_begin_[line]; }
    uint32_t end(uint32_t line) const { return line_begin_[line + 1]; }
    size_t bytes() const { return chunks_.size() * sizeof(Chunk) + line_begin_.size() * sizeof(uint32_t); }
    size_t segments() const { return segments_; }  // of all chunks

private:
    std::vector<Chunk> chunks_;
    std::vector<uint32_t> line_begin_{0};  // per line, plus one past the end
    size_t segments_ = 0;
};

}  // namespace pathlet
