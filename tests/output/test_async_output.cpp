// The asynchronous output path (frames/async_output.hpp) against the synchronous one it
// replaced: in the same render, every captured output is also read the old way in on_frame
// (read_texture + box_downsample) and written with write_image; the files must be the same
// bytes. PNG and EXR (colour, float, depth), with and without --ssaa, sharded.
#include "file_bytes.hpp"
#include "executor.hpp"
#include "frame_capture.hpp"
#include "frames/byte_readback.hpp"
#include "frames/gpu_box_filter.hpp"
#include "image_io.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace pathlet {
namespace {

namespace fs = std::filesystem;
const std::string kSrc = PATHLET_SOURCE_DIR;

fs::path scratch(const std::string& name) {
    fs::path p = fs::path(test_scratch_dir("pathlet_async_output")) / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}


std::vector<std::string> hidden_entries(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string()[0] == '.') out.push_back(e.path().string());
    return out;
}

struct Case {
    std::string graph;
    std::vector<std::string> outputs;  // the graph's captured outputs, in its order
    int ssaa = 1;
    int shard_index = 0, shard_count = 1;
};

RenderOptions options_for(const Case& c, const fs::path& out) {
    RenderOptions o;
    o.graph_path = kSrc + "/graphs/" + c.graph + ".json";
    o.sets = {"window=3"};
    o.size = {64, 48};
    o.ssaa = c.ssaa;
    o.time = {4.0, 5.0, 0.25};  // 5 frames
    o.shard_index = c.shard_index;
    o.shard_count = c.shard_count;
    o.out_dir = out.string();
    o.quiet = true;
    o.warmup = 0;
    return o;
}

// Renders once: the asynchronous path writes the files, on_frame keeps the synchronous
// path's images of the same frames; the reference files are written afterwards.
void expect_same_files(const Case& c) {
    SCOPED_TRACE(c.graph + " ssaa " + std::to_string(c.ssaa) + " shard " + std::to_string(c.shard_index) + "/" +
                 std::to_string(c.shard_count));
    const fs::path out = scratch(c.graph + "_" + std::to_string(c.ssaa) + "_" + std::to_string(c.shard_count));
    RenderOptions o = options_for(c, out);
    std::vector<Image> sync;
    std::vector<size_t> frames;
    RenderResult r = render(test_runtime(), helix_bundle_scene(), o, [&](const Executor& e, size_t frame) {
        frames.push_back(frame);
        for (const auto& name : c.outputs) {
            const Texture t = e.texture(name);
            sync.push_back(box_downsample(read_texture(t.id, t.width, t.height, 0, 4), c.ssaa));
        }
    });
    ASSERT_EQ(r.files.size(), sync.size());
    EXPECT_EQ(r.frames_read_back, frames.size());
    const fs::path ref = scratch(c.graph + "_ref");
    for (size_t i = 0; i < sync.size(); ++i) {
        const fs::path mine = r.files[i];
        EXPECT_EQ(sync[i].width, o.size.x);
        // The frame number in the name is the unsharded sequence's.
        char digits[8];
        std::snprintf(digits, sizeof digits, "%05zu", frames[i / c.outputs.size()]);
        EXPECT_NE(mine.filename().string().find(digits), std::string::npos) << mine;
        const fs::path theirs = ref / ("ref_" + std::to_string(i) + mine.extension().string());
        write_image(theirs.string(), sync[i]);
        ASSERT_TRUE(fs::exists(mine)) << mine;
        expect_same_frame_file(mine, theirs);
    }
    EXPECT_TRUE(hidden_entries(out).empty()) << "a temp file or folder was left: " << hidden_entries(out).front();
}

const std::vector<std::string> kDebugOutputs = {"color", "normal_depth", "zoom", "depth", "ao", "final"};

TEST(AsyncOutput, PngFramesAreTheSynchronousPathsBytes) {
    expect_same_files({"variant1_lineao", {"final"}, 1});
}

TEST(AsyncOutput, SupersampledPngFramesAreTheSynchronousPathsBytes) {
    // 2 puts many means exactly half-way between 8-bit levels: any rounding difference shows.
    expect_same_files({"variant1_lineao", {"final"}, 2});
    expect_same_files({"variant1_lineao", {"final"}, 3});
}

TEST(AsyncOutput, ExrAndPngOfEveryMapAreTheSynchronousPathsBytes) {
    // rgba8 colour, rgba16f normal/depth and AO, a depth texture, the final PNG.
    expect_same_files({"lineao_debug", kDebugOutputs, 1});
    expect_same_files({"lineao_debug", kDebugOutputs, 2});
}

TEST(AsyncOutput, ShardedFramesAreTheSynchronousPathsBytesUnderTheSequencesNames) {
    expect_same_files({"variant1_lineao", {"final"}, 2, 1, 2});
    expect_same_files({"lineao_debug", kDebugOutputs, 1, 0, 3});
}

TEST(AsyncOutput, TheGpuFilterAndByteReadsAreExactOnThisDriver) {
    // Not a fallback in disguise: on llvmpipe the supersampled frames are filtered on the GPU
    // and 8-bit ones read as bytes (else the tests above would pass on the CPU path alone).
    test_runtime();
    GpuBoxFilter filter;
    for (GLenum f : {GL_RGBA8, GL_RGBA16F, GL_RGBA32F, GL_RG16F, GL_R8})
        for (int factor : {2, 3, 4}) EXPECT_TRUE(filter.exact(f, factor)) << "format 0x" << std::hex << f << " x" << factor;
    for (GLenum f : {GL_RGBA8, GL_R8, GL_RG8}) EXPECT_NE(measure_byte_table(f), nullptr) << std::hex << f;
    EXPECT_EQ(measure_byte_table(GL_RGBA16F), nullptr) << "only 8-bit formats are read as bytes";
}

TEST(AsyncOutput, NothingIsReadBackWhenNothingUsesThePixels) {
    const fs::path out = scratch("unused");
    RenderOptions o = options_for({"variant1_lineao", {"final"}}, out);
    o.write_images = false;  // --no-images, bench, Python, quality
    RenderResult r = render(test_runtime(), helix_bundle_scene(), o);
    EXPECT_EQ(r.frames, 5u);
    EXPECT_EQ(r.frames_read_back, 0u);
    EXPECT_TRUE(r.files.empty());
    EXPECT_TRUE(fs::is_empty(out));
}

TEST(AsyncOutput, OnImageSeesEveryFrameInOrderWithoutFiles) {
    // --video --no-images: the first output of every frame reaches on_image (the encoder),
    // in frame order, as the synchronous path's pixels; no file is written.
    const fs::path out = scratch("on_image");
    RenderOptions o = options_for({"variant1_lineao", {"final"}, 2}, out);
    o.write_images = false;
    std::vector<Image> seen, sync;
    o.on_image = [&](const Image& img) { seen.push_back(img); };  // one call at a time
    RenderResult r = render(test_runtime(), helix_bundle_scene(), o, [&](const Executor& e, size_t) {
        const Texture t = e.texture("final");
        sync.push_back(box_downsample(read_texture(t.id, t.width, t.height, 0, 4), 2));
    });
    EXPECT_EQ(r.frames_read_back, 5u);
    ASSERT_EQ(seen.size(), 5u);
    for (size_t i = 0; i < seen.size(); ++i) EXPECT_TRUE(seen[i].pixels == sync[i].pixels) << "frame " << i;
    EXPECT_NE(sync.front().pixels, sync.back().pixels) << "the frames differ, so the order is checked";
    EXPECT_TRUE(fs::is_empty(out));
}

TEST(AsyncOutput, AFileThatCannotBeWrittenIsAClearErrorAndNothingHalfWrittenStays) {
    // Frame 1's name is taken by a folder: frame 0 is written, frame 1 fails naming its file,
    // the frames after it are dropped, no temp file or folder stays.
    const fs::path out = scratch("blocked");
    fs::create_directories(out / "variant1_lineao" / "00001.png" / "x");
    RenderOptions o = options_for({"variant1_lineao", {"final"}}, out);
    std::string error;
    try {
        render(test_runtime(), helix_bundle_scene(), o);
    } catch (const std::runtime_error& e) {
        error = e.what();
    }
    EXPECT_NE(error.find((out / "variant1_lineao" / "00001.png").string()), std::string::npos) << error;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(out / "variant1_lineao")) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"00000.png", "00001.png"})) << "frame 0 and the folder in the way";
    EXPECT_EQ(read_image((out / "variant1_lineao" / "00000.png").string()).width, 64);
    EXPECT_TRUE(hidden_entries(out).empty()) << hidden_entries(out).front();
}

}  // namespace
}  // namespace pathlet
