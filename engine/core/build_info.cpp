#include "build_info.hpp"

#include "plugin_host.hpp"

#include <pathlet_build_features.hpp>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace pathlet {

std::string bundle_marker() {
    std::ifstream in(fs::path(engine_library_dir()).parent_path() / "share" / "pathlet" / "bundle.txt");
    std::string line;
    std::getline(in, line);
    return line;
}

std::string build_description() {
    std::string with, without;
    for (const auto& [name, has] : {std::pair<const char*, bool>{"OpenImageIO", PATHLET_WITH_OPENIMAGEIO},
                                    {"Embree", PATHLET_WITH_EMBREE}, {"HDF5", PATHLET_WITH_HDF5}})
        (has ? with : without) += (has ? with : without).empty() ? name : std::string(", ") + name;
    std::string s = "build: " + std::string(without.empty() ? "full (" + with + ")"
                                                           : "lean: PNG through stb, without " + without +
                                                                 (with.empty() ? "" : "; with " + with));
    std::error_code ec;
    const fs::path lib = fs::weakly_canonical(engine_library_dir(), ec);
    const std::string marker = bundle_marker();
    if (!marker.empty())
        s += "\nruns from a bundle: " + lib.parent_path().string() + " (" + marker + ")";
    else
        s += "\nruns from: " + lib.parent_path().string() + (fs::exists(lib.parent_path() / "CMakeCache.txt") ? " (build tree)" : "");
    s += "\nshare: " + fs::weakly_canonical(engine_share_dir(), ec).string();
    return s;
}

}  // namespace pathlet
