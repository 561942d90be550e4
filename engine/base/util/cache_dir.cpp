#include "util/cache_dir.hpp"

#include <cstdlib>
#include <filesystem>

namespace pathlet {

std::string cache_dir() {
    namespace fs = std::filesystem;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "pathlet").string();
    if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "pathlet").string();
    return (fs::temp_directory_path() / "pathlet-cache").string();
}

}  // namespace pathlet
