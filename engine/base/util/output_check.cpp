#include "util/output_check.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>
#include <unistd.h>

namespace fs = std::filesystem;

namespace pathlet {
namespace {

[[noreturn]] void fail(const std::string& what, const std::string& where, const std::string& reason) {
    throw std::runtime_error("cannot write " + what + " to '" + where + "': " + reason);
}

}  // namespace

void check_output_dir(const std::string& dir, const std::string& what, bool keep) {
    const fs::path d = dir.empty() ? fs::path(".") : fs::path(dir);
    std::error_code ec;
    std::vector<fs::path> made;  // the folders this check creates, deepest last
    if (fs::exists(d, ec)) {
        if (!fs::is_directory(d, ec)) fail(what, dir, "it exists and is not a folder");
    } else {
        for (fs::path p = d; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) made.insert(made.begin(), p);
        if (!fs::create_directories(d, ec) && ec) fail(what, dir, "cannot create the folder: " + ec.message());
    }
    // access(W_OK) misses read-only mounts for root; a real probe file does not.
    std::string probe = (d / ".pathlet-write-probe-XXXXXX").string();
    int fd = mkstemp(probe.data());
    const int err = errno;
    if (fd >= 0) close(fd), unlink(probe.c_str());
    if (!keep)
        for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // empty folders only
    if (fd < 0) fail(what, dir, std::strerror(err));
}

void check_output_file(const std::string& path, const std::string& what, bool keep) {
    if (path.empty()) fail(what, path, "empty file name");
    std::error_code ec;
    if (fs::is_directory(fs::path(path), ec)) fail(what, path, "it is a folder, not a file name");
    fs::path parent = fs::path(path).parent_path();
    try {
        check_output_dir(parent.empty() ? "." : parent.string(), what, keep);
    } catch (const std::runtime_error& e) {  // name the file, not only its folder
        throw std::runtime_error(std::string(e.what()) + " (for " + path + ")");
    }
}

}  // namespace pathlet
