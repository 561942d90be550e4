// `pathlet render` stopped mid-run by SIGINT (Ctrl-C) or SIGTERM (a scheduler's time limit):
// the frames rendered until then are written completely, in sequence, nothing temporary stays
// (no frame temp, no video temp), the video is not written and the exit status says which
// signal. And a writer's error (a full disk) is a clear error naming the file, exit 1,
// nothing half-written.
#include "image_io.hpp"
#include "../support/optional_tool.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace pathlet {
namespace {

namespace fs = std::filesystem;
const std::string kData = std::string(PATHLET_SOURCE_DIR) + "/tests/engine/data/two_lines.vtk";

fs::path scratch(const std::string& name) {
    fs::path p = fs::path(PATHLET_TEST_BINARY_DIR) / "signal_runs" / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The command, started directly (no shell between us and it), its output in files.
class Running {
public:
    Running(const std::vector<std::string>& args, const fs::path& dir) : err_(dir / "stderr.txt") {
        std::vector<std::string> all = {PATHLET_CLI};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        EXPECT_EQ(posix_spawn(&pid_, PATHLET_CLI, &fa, nullptr, argv.data(), environ), 0);
        posix_spawn_file_actions_destroy(&fa);
    }
    ~Running() {
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    void signal(int sig) {
        if (pid_ > 0) ::kill(pid_, sig);
    }
    bool running() {
        if (pid_ > 0 && ::waitpid(pid_, &status_, WNOHANG) == pid_) pid_ = -1;
        return pid_ > 0;
    }
    // The exit code, or 128 + signal when killed by one; -1 when it did not end within two
    // minutes (then ~Running kills it).
    int wait() {
        for (int i = 0; i < 1200 && running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
        if (running()) return -1;
        return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
    }
    std::string err() const { return slurp(err_); }

private:
    pid_t pid_ = -1;
    int status_ = 0;
    fs::path err_;
};

// Polls until `ready` (however slow the machine); false when the command ended first.
template <class F>
bool wait_for(Running& r, F ready) {
    for (int i = 0; i < 3000; ++i) {  // 5 minutes at most
        if (ready()) return true;
        if (!r.running()) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
}

size_t pngs_in(const fs::path& dir) {
    size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) n += e.path().extension() == ".png" && e.path().filename().string()[0] != '.';
    return n;
}

// N of the command's last words "interrupted (SIGNAL): N frame(s) rendered and written"; -1
// when it did not say them.
long frames_said(const std::string& err) {
    static const std::regex said(R"(interrupted \((SIGINT|SIGTERM)\): ([0-9]+) frame\(s\) rendered and written)");
    std::smatch m;
    return std::regex_search(err, m, said) ? std::stol(m[2]) : -1;
}

// Every entry of `dir`: frames 00000.png, 00001.png, ... without a gap, each complete, and
// exactly the `frames` the command said it wrote (a stop that dropped queued frames leaves fewer).
void expect_complete_sequence(const fs::path& dir, long frames) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    ASSERT_GE(frames, 3) << "the signal came after three frames were on disk";
    ASSERT_EQ(long(names.size()), frames) << "the files on disk are the frames the command says it wrote";
    for (size_t i = 0; i < names.size(); ++i) {
        char expected[32];
        std::snprintf(expected, sizeof expected, "%05zu.png", i);
        ASSERT_EQ(names[i], expected) << "only complete frames, in sequence (no temp, no gap)";
        const Image img = read_image((dir / names[i]).string());
        EXPECT_EQ(img.width, 160);
        EXPECT_EQ(img.height, 120);
    }
}

std::vector<std::string> render_args(const fs::path& out) {
    // Far more frames than the test waits for (the signal always comes mid-run), all inside the
    // data's 0..1 s.
    return {"render", "isl", "--data", kData, "--time", "0:1:0.0001", "--size", "160x120", "--warmup", "0",
            "--out", out.string()};
}

void stop_image_sequence(int sig, const std::string& name) {
    const fs::path dir = scratch(std::string("images_") + name);
    Running r(render_args(dir / "out"), dir);
    ASSERT_TRUE(wait_for(r, [&] { return pngs_in(dir / "out" / "isl") >= 3; })) << r.err();
    r.signal(sig);
    EXPECT_EQ(r.wait(), 128 + sig) << r.err();
    EXPECT_NE(r.err().find("interrupted (" + name + ")"), std::string::npos) << r.err();
    expect_complete_sequence(dir / "out" / "isl", frames_said(r.err()));
}

TEST(RenderSignals, SigintKeepsTheFinishedFramesAndNoTemp) { stop_image_sequence(SIGINT, "SIGINT"); }
TEST(RenderSignals, SigtermKeepsTheFinishedFramesAndNoTemp) { stop_image_sequence(SIGTERM, "SIGTERM"); }

// The video's temp file (".clip.tmp-PID-N.mp4") once ffmpeg has written into it.
bool video_started(const fs::path& dir) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().filename().string().rfind(".clip.tmp-", 0) == 0 && fs::file_size(e.path(), ec) > 0) return true;
    return false;
}

void stop_video(int sig, const std::string& name, bool images) {
    PATHLET_REQUIRE_TOOLS("ffmpeg");
    const fs::path dir = scratch(std::string("video_") + name + (images ? "_images" : ""));
    std::vector<std::string> args = render_args(dir / "out");
    args.insert(args.end(), {"--video", (dir / "vid" / "clip.mp4").string()});
    if (!images) args.push_back("--no-images");
    Running r(args, dir);
    ASSERT_TRUE(wait_for(r, [&] { return video_started(dir / "vid") && (!images || pngs_in(dir / "out" / "isl") >= 3); }))
        << r.err();
    r.signal(sig);
    EXPECT_EQ(r.wait(), 128 + sig) << r.err();
    EXPECT_NE(r.err().find("the video was not written"), std::string::npos) << r.err();
    EXPECT_TRUE(fs::is_empty(dir / "vid")) << "neither the video nor its temp file stays";
    if (images) expect_complete_sequence(dir / "out" / "isl", frames_said(r.err()));
    else EXPECT_FALSE(fs::exists(dir / "out")) << "--no-images --video writes no image";
}

TEST(RenderSignals, SigintAbandonsTheVideoAndLeavesNoTemp) { stop_video(SIGINT, "SIGINT", true); }
TEST(RenderSignals, SigtermAbandonsAVideoWithoutImages) { stop_video(SIGTERM, "SIGTERM", false); }

TEST(RenderSignals, VideoWithoutImagesWritesEveryFrameAndNoPng) {
    PATHLET_REQUIRE_TOOLS("ffmpeg ffprobe");
    const fs::path dir = scratch("video_only");
    Running r({"render", "isl", "--data", kData, "--time", "0:0.4", "--size", "160x120", "--quiet", "--no-images",
               "--out", (dir / "out").string(), "--video", (dir / "clip.mp4").string()},
              dir);
    ASSERT_EQ(r.wait(), 0) << r.err();
    EXPECT_FALSE(fs::exists(dir / "out"));
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"clip.mp4", "stderr.txt"}));
    const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 '" +
                            (dir / "clip.mp4").string() + "' > '" + (dir / "probe.txt").string() + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    EXPECT_EQ(slurp(dir / "probe.txt"), "11\n") << "0:0.4 at 25 fps is 11 frames";
}

TEST(RenderSignals, AFullDiskIsAClearErrorNamingTheFileAndNothingHalfWritten) {
    // A file size limit stands in for a full disk: the encoder's write fails (EFBIG) on a
    // writer thread (a frame here is about 2 KB); the error reaches the user with the frame's file name, exit 1.
    const fs::path dir = scratch("full_disk");
    const std::string cmd = "trap '' XFSZ; ulimit -f 1; exec '" + std::string(PATHLET_CLI) + "' render isl --data '" + kData +
                            "' --time 0:0.2 --size 160x120 --quiet --out '" + (dir / "out").string() + "' 2> '" +
                            (dir / "stderr.txt").string() + "' >/dev/null";
    const int status = std::system(("bash -c \"" + cmd + "\"").c_str());
    ASSERT_TRUE(WIFEXITED(status)) << "ended by a signal, not an error: " << slurp(dir / "stderr.txt");
    EXPECT_EQ(WEXITSTATUS(status), 1) << slurp(dir / "stderr.txt");
    const std::string err = slurp(dir / "stderr.txt");
    EXPECT_NE(err.find((dir / "out" / "isl" / "00000.png").string()), std::string::npos) << err;
    EXPECT_NE(err.find("cannot write image"), std::string::npos) << err;
    EXPECT_TRUE(fs::is_empty(dir / "out" / "isl")) << "no frame, no temp: the first one did not fit";
}

}  // namespace
}  // namespace pathlet
