// Human-readable summary of a pathline or mesh file, the text of `pathlet info FILE`.
#pragma once

#include "pathline_io.hpp"

#include <string>

namespace pathlet::io {

// Throws pathlet::DataError when the file cannot be read.
std::string describe_file(const std::string& path);
// Same, with explicit array names / time step for pathline files.
std::string describe_file(const std::string& path, const LoadOptions& opts);

}  // namespace pathlet::io
