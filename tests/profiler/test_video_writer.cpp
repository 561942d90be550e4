// MP4 export through ffmpeg on PATH; skipped where ffmpeg is not installed, failed in CI
// (optional_tool.hpp).
#include "optional_tool.hpp"
#include "scratch_dir.hpp"
#include "video_writer.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace pathlet {
namespace {

Image solid(int w, int h, float v) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = 4;
    img.pixels.assign(size_t(w) * size_t(h) * 4, v);
    return img;
}

std::string run(const std::string& cmd) {
    std::string out;
    if (FILE* p = ::popen(cmd.c_str(), "r")) {
        char buf[256];
        while (std::fgets(buf, sizeof buf, p)) out += buf;
        ::pclose(p);
    }
    return out;
}

#define REQUIRE_FFMPEG() PATHLET_REQUIRE_TOOLS("ffmpeg ffprobe")

TEST(VideoWriter, WritesPaddedOddSizedVideoAtomically) {
    REQUIRE_FFMPEG();
    ScratchDir dir;
    const std::string path = dir / "clip.mp4";
    {
        VideoWriter video(path, 33, 17, 24);
        for (int i = 0; i < 12; ++i) video.add_frame(solid(33, 17, float(i) / 12.0f));
        EXPECT_FALSE(std::filesystem::exists(path)) << "only complete files appear under the name";
        video.close();
        EXPECT_EQ(video.frames(), 12u);
    }
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"clip.mp4"});
    EXPECT_GT(std::filesystem::file_size(path), 0u);
    const std::string probe = run("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                  "stream=width,height,nb_read_frames -of csv=p=0 '" + path + "'");
    EXPECT_EQ(probe, "34,18,12\n");  // padded to even
}

TEST(VideoWriter, WrongFrameSizeIsRejected) {
    REQUIRE_FFMPEG();
    ScratchDir dir;
    VideoWriter video(dir / "clip.mp4", 16, 16, 30);
    EXPECT_THROW(video.add_frame(solid(8, 8, 0)), std::invalid_argument);
}

TEST(VideoWriter, FfmpegFailureSurfacesItsStderrAndSurvivesSigpipe) {
    REQUIRE_FFMPEG();
    ScratchDir dir;
    const std::string path = dir / "no/such/dir/clip.mp4";
    std::string msg;
    try {
        VideoWriter video(path, 512, 512, 30);  // 1 MiB frames: writes outlive ffmpeg -> EPIPE
        for (int i = 0; i < 50; ++i) video.add_frame(solid(512, 512, 0.5f));
        video.close();
    } catch (const std::runtime_error& e) {
        msg = e.what();
    }
    ASSERT_FALSE(msg.empty()) << "writing into a missing directory must fail";
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << "ffmpeg's own words: " << msg;
    EXPECT_TRUE(dir.entries().empty());
}

TEST(VideoWriter, AbandonedWriterRemovesItsTempFile) {
    REQUIRE_FFMPEG();
    ScratchDir dir;
    {
        VideoWriter video(dir / "clip.mp4", 16, 16, 30);
        video.add_frame(solid(16, 16, 0.2f));
    }  // no close(): e.g. an exception while rendering
    EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace pathlet
