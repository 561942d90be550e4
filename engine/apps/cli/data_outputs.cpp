#include "data_outputs.hpp"

#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "util/output_check.hpp"

namespace pathlet::cli {

void DataOutputs::declare(Args& a, const std::string& wall_help) {
    a.option("output", lines, "OUT", "pathlines to write (.vtp, .vtk, .pathlet); required")
        .short_name('o')
        .option("wall", wall, "OUT.glb", wall_help);
}

void DataOutputs::check() const {
    if (lines.empty()) throw UsageError("missing -o OUT");
    check_output_file(lines, "the pathlines");
    io::format_from_extension(lines);
    if (!wall.empty()) check_output_file(wall, "the wall");
}

void DataOutputs::write_lines(const Pathlines& p) const { io::save_pathlines(p, lines, io::format_from_extension(lines)); }

void DataOutputs::write_wall(const Mesh& m) const {
    if (!wall.empty()) io::save_mesh(m, wall);
}

}  // namespace pathlet::cli
