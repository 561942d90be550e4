#include "util/cache_dir.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace pathlet {

namespace {

namespace fs = std::filesystem;

// The user's own folder in the temporary directory, made 0700 if missing; what is there
// already must be this user's directory (not a link) that no one else may write.
std::string private_temp_folder() {
    const std::string dir = (fs::temp_directory_path() / ("pathlet-cache-" + std::to_string(::getuid()))).string();
    if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
        throw std::runtime_error("cache folder " + dir + ": cannot make it (" + std::strerror(errno) +
                                 "); set HOME or XDG_CACHE_HOME");
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0)
        throw std::runtime_error("cache folder " + dir + ": " + std::strerror(errno) + "; set HOME or XDG_CACHE_HOME");
    std::string why;
    if (!S_ISDIR(st.st_mode)) why = "is not a directory (a link or a file someone put there)";
    else if (st.st_uid != ::getuid()) why = "belongs to another user (uid " + std::to_string(st.st_uid) + ")";
    else if (st.st_mode & (S_IWGRP | S_IWOTH)) why = "may be written by other users";
    if (!why.empty())
        throw std::runtime_error("cache folder " + dir + " " + why + ": not used; set HOME or XDG_CACHE_HOME");
    return dir;
}

}  // namespace

std::string cache_dir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
        return (fs::path(xdg) / "pathlet").string();
    if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "pathlet").string();
    return private_temp_folder();
}

}  // namespace pathlet
