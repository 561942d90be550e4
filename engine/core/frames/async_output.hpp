// The render's output side: what a frame's captured outputs become (files, the on_image
// consumer) without the render thread waiting for the GPU or for an encoder.
//
//   render thread: capture()  -> [supersampled: GPU box filter] -> pixel-pack buffer + fence
//                  poll()     -> fence signalled: the bytes become a job (never waits)
//   writers:       work       -> the Image (flip, divide, ...), encoded under a temp name
//                  commit     -> renamed into place / handed to on_image, in frame order
//
// Memory is bounded twice: `ring_depth` frames in the pack buffers and `max_queued` images
// in the writers (the render thread waits when either is full). The files and images are
// those of read_texture + box_downsample + write_image, bit for bit.
#pragma once

#include "frames/gpu_box_filter.hpp"
#include "frames/gpu_depth_copy.hpp"
#include "frames/ordered_jobs.hpp"
#include "frames/raw_frame.hpp"
#include "frames/readback_ring.hpp"

#include <pathlet/pass.hpp>

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace pathlet {

class AsyncOutput {
public:
    struct Options {
        int ssaa = 1;             // captures are ssaa x the size; what comes out is the size
        size_t ring_depth = 3;    // frames in flight between the GPU and the writers
        int threads = 0;          // writer threads; 0: min(4, cores)
        size_t max_queued = 0;    // images between read-back and commit; 0: threads + 2
        std::function<void(const Image&)> on_image;  // on a writer, in frame order, one at a time
        bool quiet = true;        // no note when supersampling falls back to the CPU filter
    };
    struct Capture {
        std::string what;      // "output 'final'", for errors
        Texture tex;           // the resource, at ssaa x the size
        std::string file;      // written there (temp name, then rename); "" = not written
        bool to_image = false; // handed to on_image
        // Handed this capture's image, on a writer in frame order (a caller reading a resource back).
        std::function<void(const Image&)> sink{};
        // The box filter's factor: 0 = Options::ssaa (a render-size output); 1 keeps a texture of
        // another size as it is.
        int factor = 0;
    };

    explicit AsyncOutput(Options o);
    // Without finish(): abandons what is not written yet (no temp file stays). GL context current.
    ~AsyncOutput();
    AsyncOutput(const AsyncOutput&) = delete;
    AsyncOutput& operator=(const AsyncOutput&) = delete;

    // After a frame: queues the read-back of its captures (nothing for an empty list). Waits
    // only when the ring or the writers are full; rethrows a writer's error.
    void capture(const std::vector<Capture>& captures);
    void poll();    // hands every finished read-back to the writers, never waiting for the GPU
    void finish();  // everything written and committed; rethrows a writer's error

    size_t frames_captured() const { return frames_captured_; }
    size_t frames_written() const { return frames_written_.load(); }  // every capture committed
    int threads() const { return jobs_.threads(); }
    size_t max_queued() const { return jobs_.capacity(); }
    uint64_t bytes_read_back() const { return ring_.bytes_copied(); }  // into pack buffers, so far

private:
    // How a format is read back: the layout, glGetTextureImage's format and type, the GPU's
    // work before it (the box filter's sums, depth as R32F).
    struct Plan {
        RawFrame::Layout layout = RawFrame::Layout::Floats;
        int factor = 1;
        std::shared_ptr<const ByteTable> table;
        GLenum format = GL_RGBA, type = GL_FLOAT;
        int channels = 4;
        bool half = false, depth_copy = false;
    };
    Plan plan_for(const Capture& c);
    void submit(RawFrame&& raw, const Capture& c, bool last_of_frame);
    std::string staging_dir(const std::string& file);

    Options opt_;
    OrderedJobs jobs_;
    ReadbackRing ring_;
    GpuBoxFilter filter_;
    GpuDepthCopy depth_copy_;
    std::map<GLenum, std::shared_ptr<const ByteTable>> tables_;  // nullptr: not read as bytes
    std::map<std::pair<GLenum, int>, Plan> plans_;               // by internal format and factor
    std::map<std::string, std::string> staging_;  // output folder -> its temp folder
    size_t frames_captured_ = 0;
    uint64_t job_seq_ = 0;
    std::atomic<size_t> frames_written_{0};
    bool noted_cpu_filter_ = false;
};

}  // namespace pathlet
