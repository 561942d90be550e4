// Nothing half-written: every output goes to a temporary name beside the target and is
// renamed into place only when complete (rename is atomic within one file system).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace pathlet {

// A temporary path in the same directory that keeps the extension (so writers that pick
// a format by extension, like OpenImageIO, still work): "dir/.name.tmp-1234-0.png".
std::string temp_path_for(const std::string& path);

// A temporary folder in `dir` (".name.tmp-PID-N.d", created, held like a temp file) for files
// that are finished in it and renamed out of it later (the render's writers, which move frames
// into place in frame order). discard_temp() removes it with what is left in it.
std::string temp_dir_in(const std::string& dir, const std::string& name);
// Removes a temp file or folder of this process (nothing when it is gone) and lets it go.
void discard_temp(const std::string& tmp);

// Removes temporaries (".name.tmp-PID-N.ext", and temp folders with their content) in `dir`
// whose writing process no longer runs: what a killed render leaves. Files under their final
// names are always complete.
void remove_stale_temps(const std::string& dir);

// Renames tmp to path; on failure removes tmp and throws std::runtime_error naming both.
void commit_temp(const std::string& tmp, const std::string& path);

// Writes bytes to path atomically. Throws std::runtime_error naming the file on failure.
void write_file_atomic(const std::string& path, std::string_view bytes);

// Streams into a temp file with `fill`, then renames. If `fill` throws, the temp file is
// removed and the exception propagates; the target is left untouched.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& fill);

}  // namespace pathlet
