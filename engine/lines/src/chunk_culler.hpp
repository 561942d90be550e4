// The line kit's culling (private to the kit; lines::Drawer uses it): the time window's ranges
// cut into chunks (pathlet/line_chunks.hpp), chunks outside the view frustum dropped, and
// two-phase occlusion culling against the pass's own depth buffer:
//
//   phase 1  the chunks that were visible last frame are drawn;
//   test     the pass's depth after phase 1, reduced on the GPU to the farthest depth per
//            8x8-pixel tile (line_tile_depth.frag) and read back, hides every other chunk whose
//            nearest possible depth lies behind every tile its screen rectangle touches;
//   phase 2  the rest is drawn (a camera jump or a new pathlet shows here, never missing);
//   then     the final depth decides which chunks phase 1 draws next frame.
//
// Conservative by construction: a chunk's box is grown by the widest the line can be drawn
// (half the width times the width hook's cap), so the tube's bulge towards the viewer is
// inside it, and a box reaching behind the camera is never hidden. Culled chunks would have
// failed the depth test everywhere; only the order of equal-depth draws can differ.
#pragma once

#include <pathlet/gpu_scene.hpp>

#include <chrono>

#include <vector>

namespace pathlet::lines {

class ChunkCuller {
public:
    struct Stats {
        size_t chunks = 0;          // chunk pieces in the window
        size_t frustum_culled = 0;  // outside the view
        size_t phase1 = 0, phase2 = 0, occluded = 0;
        double cpu_ms = 0;          // cutting, frustum and occlusion tests on the CPU, per frame
    };

    // Cuts the window's ranges into chunk pieces; those outside the frustum are dropped, those
    // visible last frame form phase 1 (all of them without `occlusion`: one draw, no joins
    // drawn twice, which matters where every fragment counts, as in OIT). `grow`: world units
    // to widen every box by.
    void split(const GpuScene::Ranges& window, const LineChunks& chunks, const glm::vec3* points,
               const glm::mat4& view_proj, float grow, bool occlusion);
    const GpuScene::Ranges& phase1() const { return phase1_; }

    // The farthest depth per kTile x kTile tile (rows bottom-up as GL's), `tiles` of them;
    // null: no depth to test against.
    struct TileDepth {
        const float* farthest = nullptr;
        glm::ivec2 tiles{0};
    };
    static constexpr int kTile = 8;  // = the tile of line_tile_depth.frag

    // Whether phase 1 drew anything (a depth buffer of nothing hides nothing).
    bool drew_phase1() const { return !p1_.empty(); }
    // After phase 1: the rest that the depth does not hide (all of it without depth).
    void test_rest(TileDepth depth);
    const GpuScene::Ranges& phase2() const { return phase2_; }

    // After phase 2: the chunks the final depth does not hide are next frame's phase 1.
    void remember(TileDepth depth);

    const Stats& stats() const { return stats_; }

private:
    struct Piece {
        uint32_t chunk;
        GLint first;
        GLsizei count;
        uint32_t line;
        Bounds box;  // of the piece's points, grown (the chunk's when the piece is all of it)
    };
    bool hidden(const Bounds& box, TileDepth depth) const;
    static void append(GpuScene::Ranges& r, const Piece& p);

    glm::mat4 view_proj_{1.0f};
    std::vector<Piece> p1_, rest_, drawn2_;
    GpuScene::Ranges phase1_, phase2_;
    std::vector<uint8_t> visible_;  // per chunk: drawn and not hidden last frame
    Stats stats_;
};

}  // namespace pathlet::lines
