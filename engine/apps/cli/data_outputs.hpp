// The outputs of the commands that generate data (phantom, trace): -o OUT (pathlines) and
// --wall OUT.glb (vessel wall), declared once, checked before minutes of work (folder writable,
// format known from the extension) and written at the end, each atomically.
#pragma once

#include "args.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet::cli {

struct DataOutputs {
    std::string lines, wall;
    void declare(Args& a, const std::string& wall_help);
    // UsageError without -o; std::runtime_error naming a place that cannot take the file.
    void check() const;
    void write_lines(const Pathlines& p) const;
    void write_wall(const Mesh& m) const;  // only when --wall was given
};

}  // namespace pathlet::cli
