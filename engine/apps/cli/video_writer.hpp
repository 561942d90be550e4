// Optional MP4 export through an `ffmpeg` executable found on PATH (a runtime tool, never
// linked). Raw RGBA frames go down a pipe; the file appears under its name only once ffmpeg
// has finished successfully. Image sequences (image_io.hpp) stay the robust default.
#pragma once

#include "image_io.hpp"

#include <cstdio>
#include <string>
#include <sys/types.h>

namespace pathlet {

class VideoWriter {
public:
    static std::string find_ffmpeg();  // full path of ffmpeg on PATH, or ""
    static bool available() { return !find_ffmpeg().empty(); }

    // Starts ffmpeg (libx264, yuv420p; odd sizes are padded to even). Throws
    // std::runtime_error when ffmpeg is missing or cannot be started.
    VideoWriter(std::string path, int width, int height, double fps);
    ~VideoWriter();  // without close(): stops ffmpeg, abandons the video, removes the temp file
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // Frame must be width x height, top row first. Throws with ffmpeg's stderr if it quit.
    void add_frame(const Image& frame);
    // Waits for ffmpeg and renames the file into place; throws with ffmpeg's stderr on failure.
    void close();
    size_t frames() const { return frames_; }

private:
    int wait_ffmpeg();  // closes the pipe, waits: ffmpeg's wait status, -1 if there is no pipe
    // Cleans up and throws, with ffmpeg's exit status (from wait_ffmpeg) and stderr.
    [[noreturn]] void fail(const std::string& what, int status);
    std::string ffmpeg_stderr() const;

    std::string path_, tmp_, err_path_;
    int width_, height_;
    FILE* pipe_ = nullptr;
    pid_t pid_ = -1;
    size_t frames_ = 0;
};

}  // namespace pathlet
