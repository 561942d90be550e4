#include "video_writer.hpp"

#include "util/atomic_file.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace fs = std::filesystem;

namespace pathlet {

namespace {

// If ffmpeg exits early (bad size, full disk) our next write gets EPIPE, and SIGPIPE would
// kill the whole process. Block it in this thread while writing and swallow one we caused,
// instead of changing the process-wide disposition behind the application's back.
class SigpipeGuard {
public:
    SigpipeGuard() {
        sigset_t pipe_only = only_sigpipe();
        pthread_sigmask(SIG_BLOCK, &pipe_only, &old_);
        sigset_t pending;
        sigpending(&pending);
        was_pending_ = sigismember(&pending, SIGPIPE) == 1;
    }
    ~SigpipeGuard() {
        sigset_t pending;
        sigpending(&pending);
        if (!was_pending_ && sigismember(&pending, SIGPIPE) == 1) {
            sigset_t pipe_only = only_sigpipe();
            timespec zero{0, 0};
            sigtimedwait(&pipe_only, nullptr, &zero);
        }
        pthread_sigmask(SIG_SETMASK, &old_, nullptr);
    }

private:
    static sigset_t only_sigpipe() {
        sigset_t s;
        sigemptyset(&s);
        sigaddset(&s, SIGPIPE);
        return s;
    }
    sigset_t old_;
    bool was_pending_ = false;
};

std::string make_stderr_file() {
    std::string templ = (fs::temp_directory_path() / "pathlet-ffmpeg-XXXXXX").string();
    int fd = ::mkstemp(templ.data());
    if (fd < 0) throw std::runtime_error("cannot create a temp file for ffmpeg's messages in " + templ);
    ::close(fd);
    return templ;
}

// posix_spawn's parts, freed however the start ends.
struct SpawnParts {
    posix_spawn_file_actions_t files;
    posix_spawnattr_t attr;
    SpawnParts() {
        posix_spawn_file_actions_init(&files);
        posix_spawnattr_init(&attr);
    }
    ~SpawnParts() {
        posix_spawn_file_actions_destroy(&files);
        posix_spawnattr_destroy(&attr);
    }
};

}  // namespace

std::string VideoWriter::find_ffmpeg() {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        fs::path candidate = fs::path(dir.empty() ? "." : dir) / "ffmpeg";
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return "";
}

VideoWriter::VideoWriter(std::string path, int width, int height, double fps)
    : path_(std::move(path)), width_(width), height_(height) {
    const std::string ffmpeg = find_ffmpeg();
    if (ffmpeg.empty()) throw std::runtime_error(path_ + ": cannot write video: ffmpeg not found on PATH");
    if (width <= 0 || height <= 0 || !(fps > 0))
        throw std::runtime_error(path_ + ": cannot write video: bad size or frame rate");
    // What a killed render left here (ffmpeg finishes a temp file when its input ends).
    const std::string dir = fs::path(path_).parent_path().string();
    remove_stale_temps(dir.empty() ? "." : dir);
    tmp_ = temp_path_for(path_);  // keeps the extension, which picks ffmpeg's container
    err_path_ = make_stderr_file();

    std::ostringstream rate;
    rate << fps;
    const std::vector<std::string> args = {
        ffmpeg, "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-f", "rawvideo", "-pixel_format", "rgba",
        "-video_size", std::to_string(width) + "x" + std::to_string(height), "-framerate", rate.str(), "-i", "pipe:0",
        "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",  // yuv420p needs even sizes
        "-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18",
        "-preset", "veryfast",  // frames encode while the next render on the same cores; as small at crf 18
        "-movflags", "+faststart", tmp_};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    // ffmpeg reads raw frames from a pipe and writes its messages to a file. It runs in a
    // process group of its own, so a Ctrl-C in the terminal reaches only us: we decide what
    // becomes of the video (render: abandoned, and the temp file removed).
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        std::error_code ec;
        fs::remove(err_path_, ec);
        discard_temp(tmp_);
        throw std::runtime_error(path_ + ": cannot start ffmpeg (pipe)");
    }
    SpawnParts sp;
    posix_spawn_file_actions_adddup2(&sp.files, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addopen(&sp.files, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&sp.files, STDERR_FILENO, err_path_.c_str(), O_WRONLY | O_TRUNC, 0600);
    sigset_t none, defaults;
    sigemptyset(&none);  // not the caller's mask (SigpipeGuard blocks SIGPIPE while writing)
    sigemptyset(&defaults);
    for (int sig : {SIGPIPE, SIGINT, SIGTERM}) sigaddset(&defaults, sig);
    posix_spawnattr_setsigmask(&sp.attr, &none);
    posix_spawnattr_setsigdefault(&sp.attr, &defaults);
    posix_spawnattr_setpgroup(&sp.attr, 0);
    posix_spawnattr_setflags(&sp.attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    const int rc = ::posix_spawn(&pid_, ffmpeg.c_str(), &sp.files, &sp.attr, argv.data(), environ);
    ::close(fds[0]);
    if (rc == 0) pipe_ = ::fdopen(fds[1], "w");
    if (!pipe_) {
        ::close(fds[1]);
        if (rc == 0) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
        pid_ = -1;
        std::error_code ec;
        fs::remove(err_path_, ec);
        discard_temp(tmp_);
        throw std::runtime_error(path_ + ": cannot start ffmpeg: " + std::strerror(rc ? rc : errno));
    }
}

VideoWriter::~VideoWriter() {
    // Abandoned (an error, or an interrupted render): ffmpeg's work is not wanted, so it is
    // stopped rather than waited for while it encodes what it has.
    if (pid_ > 0) ::kill(pid_, SIGKILL);
    wait_ffmpeg();
    std::error_code ec;
    if (!tmp_.empty()) discard_temp(tmp_);
    if (!err_path_.empty()) fs::remove(err_path_, ec);
}

int VideoWriter::wait_ffmpeg() {
    if (!pipe_) return -1;
    {
        SigpipeGuard guard;  // fclose flushes what is still buffered
        std::fclose(pipe_);
    }
    pipe_ = nullptr;
    int status = -1;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {}
    pid_ = -1;
    return status;
}

std::string VideoWriter::ffmpeg_stderr() const {
    std::ifstream in(err_path_);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    if (text.size() > 2000) text = "..." + text.substr(text.size() - 2000);
    return text.empty() ? "(ffmpeg printed nothing)" : text;
}

void VideoWriter::fail(const std::string& what, int status) {
    std::string msg = path_ + ": " + what;
    if (status != -1 && WIFEXITED(status)) msg += " (ffmpeg exit status " + std::to_string(WEXITSTATUS(status)) + ")";
    else if (status != -1 && WIFSIGNALED(status)) msg += " (ffmpeg killed by signal " + std::to_string(WTERMSIG(status)) + ")";
    msg += ": " + ffmpeg_stderr();
    std::error_code ec;
    discard_temp(tmp_);
    fs::remove(err_path_, ec);
    tmp_.clear();
    err_path_.clear();
    throw std::runtime_error(msg);
}

void VideoWriter::add_frame(const Image& frame) {
    if (!pipe_) throw std::logic_error(path_ + ": add_frame after close");
    if (frame.width != width_ || frame.height != height_)
        throw std::invalid_argument(path_ + ": frame is " + std::to_string(frame.width) + "x" +
                                    std::to_string(frame.height) + ", video is " + std::to_string(width_) + "x" +
                                    std::to_string(height_));
    const std::vector<uint8_t> rgba = to_rgba8(frame);
    size_t written = 0;
    bool ok = false;
    {
        SigpipeGuard guard;
        written = std::fwrite(rgba.data(), 1, rgba.size(), pipe_);
        ok = written == rgba.size() && std::fflush(pipe_) == 0 && !std::ferror(pipe_);
    }
    if (!ok) fail("ffmpeg stopped accepting frames at frame " + std::to_string(frames_), wait_ffmpeg());
    ++frames_;
}

void VideoWriter::close() {
    if (!pipe_) throw std::logic_error(path_ + ": VideoWriter closed twice");
    if (frames_ == 0) fail("no frames were added", wait_ffmpeg());
    const int status = wait_ffmpeg();
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) fail("ffmpeg failed", status);
    commit_temp(tmp_, path_);
    tmp_.clear();
    std::error_code ec;
    fs::remove(err_path_, ec);
    err_path_.clear();
}

}  // namespace pathlet
