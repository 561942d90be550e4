// One render, prepared once for every front end (the command's render, bench, quality and
// view, and Python): the graph loaded with the caller's --set (hook paths made the user's where
// the user gave them) and compiled once at the render size with its pixel scale, before any data
// is read or any GL work is done; then run over a scene, every frame's captured outputs and the
// resources a caller reads back going through the one asynchronous GPU read-back
// (frames/async_output.hpp).
#pragma once

#include "renderer.hpp"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pathlet {

class Executor;

// A resource a caller takes every frame (Python's outputs, a quality measure): handed over as an
// Image on a writer thread, in frame order, after the render-size ones are box-filtered back to
// the picture's size.
struct ReadBack {
    std::string resource;  // a resource of the compiled graph, or PASS.PIN
    std::function<void(size_t frame, const Image&)> take;
};

class RenderJob {
public:
    // Loads opt.graph_path with opt.sets and compiles it for opt.size x opt.ssaa (pixel scale
    // opt.ssaa), opt.keep and every read-back kept out of the pool. GraphError naming every
    // problem; std::invalid_argument for a read-back the graph lacks.
    RenderJob(Runtime& rt, RenderOptions opt, Runtime::SetsFrom from = Runtime::SetsFrom::file,
              std::vector<ReadBack> read_backs = {});

    const GraphFile& graph() const { return graph_; }
    const CompiledGraph& compiled() const { return compiled_; }
    const RenderOptions& options() const { return opt_; }
    // What a run may set once the inputs are known: the time range, and the caller's view of the
    // frames (RenderOptions' on_image, on_frames, stop). The size, the graph and its --set are
    // the compiled graph's and stay as the constructor took them, so no setter changes them.
    void set_time(const TimeRange& time) { opt_.time = time; }
    void set_callbacks(decltype(RenderOptions::on_image) on_image, decltype(RenderOptions::on_frames) on_frames,
                       decltype(RenderOptions::stop) stop) {
        opt_.on_image = std::move(on_image);
        opt_.on_frames = std::move(on_frames);
        opt_.stop = std::move(stop);
    }
    // One more resource read back every frame (before run()); std::invalid_argument, naming the
    // graph's resources, where it has none of that name.
    void read_back(ReadBack rb);

    // Renders opt.time over `scene` on the runtime's GL context. `on_frame` (optional) sees the
    // executor after each frame (tests read textures).
    RenderResult run(const Scene& scene, const std::function<void(const Executor&, size_t frame)>& on_frame = {});

private:
    class Loop;
    Runtime& rt_;
    RenderOptions opt_;
    GraphFile graph_;
    CompiledGraph compiled_;
    std::vector<ReadBack> read_backs_;
};

}  // namespace pathlet
