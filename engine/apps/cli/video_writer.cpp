#include "video_writer.hpp"

#include "util/atomic_file.hpp"
#include "util/text.hpp"

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

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

using text::shell_quote;

std::string make_stderr_file() {
    std::string templ = (fs::temp_directory_path() / "pathlet-ffmpeg-XXXXXX").string();
    int fd = ::mkstemp(templ.data());
    if (fd < 0) throw std::runtime_error("cannot create a temp file for ffmpeg's messages in " + templ);
    ::close(fd);
    return templ;
}

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
    tmp_ = temp_path_for(path_);  // keeps the extension, which picks ffmpeg's container
    err_path_ = make_stderr_file();

    std::ostringstream cmd;
    cmd << shell_quote(ffmpeg) << " -hide_banner -loglevel error -y -f rawvideo -pixel_format rgba"
        << " -video_size " << width << "x" << height << " -framerate " << fps << " -i -"
        << " -vf " << shell_quote("pad=ceil(iw/2)*2:ceil(ih/2)*2")  // yuv420p needs even sizes
        << " -c:v libx264 -pix_fmt yuv420p -crf 18 -movflags +faststart " << shell_quote(tmp_) << " 2>"
        << shell_quote(err_path_);
    pipe_ = ::popen(cmd.str().c_str(), "w");
    if (!pipe_) {
        std::error_code ec;
        fs::remove(err_path_, ec);
        throw std::runtime_error(path_ + ": cannot start ffmpeg");
    }
}

VideoWriter::~VideoWriter() {
    wait_ffmpeg();
    std::error_code ec;
    if (!tmp_.empty()) fs::remove(tmp_, ec);
    if (!err_path_.empty()) fs::remove(err_path_, ec);
}

int VideoWriter::wait_ffmpeg() {
    if (!pipe_) return -1;
    SigpipeGuard guard;  // pclose flushes what is still buffered
    int status = ::pclose(pipe_);
    pipe_ = nullptr;
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
    fs::remove(tmp_, ec);
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
