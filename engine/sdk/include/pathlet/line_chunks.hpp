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
    static constexpr uint32_t kSegments = 32;

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

private:
    std::vector<Chunk> chunks_;
    std::vector<uint32_t> line_begin_{0};  // per line, plus one past the end
};

}  // namespace pathlet
