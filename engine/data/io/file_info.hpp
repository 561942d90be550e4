// Human-readable summary of a pathline or mesh file, the text of `pathlet info FILE`.
#pragma once

#include "pathline_io.hpp"

#include <functional>
#include <string>

namespace pathlet::io {

// Throws pathlet::DataError when the file cannot be read.
std::string describe_file(const std::string& path);
// Lines a caller adds to a pathline file's summary (the GPU memory it would take), or nothing.
using DescribeMore = std::function<std::string(const Pathlines&)>;
// Same, with explicit array names / time step for pathline files.
std::string describe_file(const std::string& path, const LoadOptions& opts, const DescribeMore& more = {});
// The summary of pathlines already loaded, from "kind:" on (`r`: what loading them reported).
std::string describe_pathlines(const Pathlines& p, const LoadReport& r, const DescribeMore& more = {});

}  // namespace pathlet::io
