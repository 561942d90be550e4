// pathlet trace FIELD -o OUT: dense pathlines (and optionally the wall) from a velocity volume.
#include "args.hpp"
#include "util/output_check.hpp"
#include "commands.hpp"
#include "io/mesh_io.hpp"
#include "io/pathline_io.hpp"
#include "io/units.hpp"
#include "scene_args.hpp"
#include "trace/field_readers.hpp"
#include "trace/marching_cubes.hpp"
#include "fraction_progress.hpp"
#include "trace/tracer.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace pathlet::cli {
namespace {

// "period,peak" -> Pulsatile.
trace::Pulsatile parse_pulsatile(const std::string& s) {
    std::istringstream in(s);
    trace::Pulsatile p;
    char comma = 0;
    if (!(in >> p.period >> comma >> p.peak) || comma != ',' || !(p.period > 0) || !(p.peak > 0) || !in.eof())
        throw UsageError("--pulsatile expects PERIOD,PEAK (seconds, factor), e.g. 0.8,2.85; got '" + s + "'");
    return p;
}

int run(std::vector<std::string> argv) {
    Args a("trace", "Traces dense pathlines through a velocity volume (study report I.b): seeds until every vessel\n"
                    "voxel is crossed by a line, RK4 backward and forward in time from each seed, drops lines that\n"
                    "are too short or run alongside accepted ones, smooths with a binomial filter, resamples.\n"
                    "Inputs: VTK legacy STRUCTURED_POINTS .vtk, VTK XML .vti, 4DFlowNet .h5 (u, v, w, mask, dx).\n"
                    "The vessel is the file's mask (>= 0.5), or SCALARS > --mask-threshold, or the whole grid.\n"
                    "The result does not depend on --threads. Exit status: 0 ok, 1 bad data, 2 bad usage.");
    a.positional("FIELD", "velocity volume (.vtk, .vti, .h5)")
        .option("output", "OUT", "", "pathlines to write (.vtp, .vtk, .pathlet); required")
        .short_name('o')
        .option("wall", "OUT.glb", "", "also write the vessel wall (marching cubes of the mask) as .glb/.gltf/.stl/.obj")
        .option("wall-pieces", "SHARE", "0.01",
                "drop wall pieces with fewer triangles than SHARE of the largest (a thresholded scan's noise specks); 0 keeps all")
        .option("mask-threshold", "X", "", "vessel = scalars > X (e.g. 175 for carotid.vtk)")
        .option("velocity-scale", "S", "1", "multiply velocities (e.g. to convert units to world units/s)")
        .option("units", "LENGTH[,VELOCITY]", "",
                "units written with the pathlines where the field does not say them (the .h5 layout does: mm, mm/s)")
        .option("step", "VOXELS", "0.25", "RK4 step length in voxels")
        .option("max-dt", "SECONDS", "0.02", "largest time step")
        .option("duration", "SECONDS", "10", "release window: seeds released over [0, duration); lines clipped to it")
        .option("line-time", "SECONDS", "4", "longest duration of one line")
        .option("min-length", "L", "0", "drop lines shorter than L (world units)")
        .option("min-distance", "D", "0", "drop lines running within D of accepted lines (0: off)")
        .option("close-fraction", "F", "0.8", "... when this fraction of their points is that close")
        .option("smooth", "N", "2", "binomial smoothing passes")
        .option("resample", "L", "0", "distance between output points (0: one voxel)")
        .option("pulsatile", "PERIOD,PEAK", "", "modulate a steady field with the systole/diastole waveform")
        .flag("periodic", "frames repeat over the cycle (time-resolved input)")
        .flag("forward-only", "integrate forward from the seed only")
        .option("max-lines", "N", "0", "stop after N lines (0: no limit)")
        .option("seed", "N", "1", "seeding hash seed")
        .option("threads", "N", "0", "worker threads (0: all cores)")
        .example("pathlet trace carotid.vtk --mask-threshold 175 -o carotid.vtp --wall carotid.glb",
                 "steady carotid field, vessel from the scalar volume")
        .example("pathlet trace example_data_HR.h5 -o arch.vtp --pulsatile 0.8,2.85 --min-length 10 --min-distance 0.6",
                 "4DFlowNet aortic arch made pulsatile, sparser lines")
        .example("pathlet trace flow.vti -o flow.pathlet --periodic --duration 3", "time-resolved .vti frames, cached output");
    if (!a.parse(argv)) return 0;
    const std::string out = a.get("output");
    if (out.empty()) throw UsageError("missing -o OUT");
    // Before minutes of tracing: the outputs' folders must be writable and their formats known.
    check_output_file(out, "the pathlines");
    io::format_from_extension(out);
    if (!a.get("wall").empty()) check_output_file(a.get("wall"), "the wall");

    trace::TraceOptions o;
    o.step = float(a.number("step"));
    o.max_dt = float(a.number("max-dt"));
    o.time_end = float(a.number("duration"));
    o.max_line_time = float(a.number("line-time"));
    o.min_length = float(a.number("min-length"));
    o.min_distance = float(a.number("min-distance"));
    o.close_fraction = float(a.number("close-fraction"));
    o.smooth_passes = int(a.integer("smooth"));
    o.resample_step = float(a.number("resample"));
    o.periodic = a.has("periodic");
    o.bidirectional = !a.has("forward-only");
    o.max_lines = size_t(std::max(0L, a.integer("max-lines")));
    o.seed = uint64_t(a.integer("seed"));
    o.threads = int(a.integer("threads"));
    if (a.has("pulsatile")) o.pulsatile = parse_pulsatile(a.get("pulsatile"));
    if (!(o.step > 0) || !(o.max_dt > 0) || !(o.time_end > 0) || !(o.max_line_time > 0) || o.smooth_passes < 0 || o.threads < 0)
        throw UsageError("--step, --max-dt, --duration, --line-time must be > 0; --smooth, --threads >= 0");
    const float vscale = float(a.number("velocity-scale"));
    const float wall_pieces = float(a.number("wall-pieces"));
    if (!(wall_pieces >= 0.0f && wall_pieces <= 1.0f)) throw UsageError("--wall-pieces must lie in 0..1");
    const std::string units = units_option(a);

    {
        io::format_from_extension(out);  // fail on a bad extension before the work
        FractionProgress progress("trace");
        trace::VelocityField field = trace::load_velocity_field(a.pos("FIELD"));
        if (a.has("mask-threshold")) field.mask_from_scalars(float(a.number("mask-threshold")));
        if (vscale != 1.0f) {
            for (auto& f : field.frames)
                for (auto& v : f) v *= vscale;
            field.units.velocity = "";  // scaled into something only the user knows: --units says it
        }
        trace::TraceStats st;
        Pathlines lines = trace::trace_pathlines(field, o, progress.callback(), &st);
        io::apply_units_option(lines.units, units);
        trace::PieceStats pieces;
        if (!a.get("wall").empty())
            io::save_mesh(trace::vessel_wall(field, wall_pieces, &pieces, progress.callback()), a.get("wall"));
        io::save_pathlines(lines, out, io::format_from_extension(out));
        progress.finish("done");
        std::fprintf(stderr, "pathlet trace: %zu lines, %zu points; %zu of %zu vessel voxels crossed; %zu seeds "
                             "(%zu too short, %zu too close); %.1f s\n",
                     lines.line_count(), lines.point_count(), st.covered_voxels, st.vessel_voxels, st.candidates,
                     st.rejected_short, st.rejected_close, progress.seconds());
        if (pieces.pieces > pieces.kept)
            std::fprintf(stderr, "pathlet trace: wall: kept %zu of %zu pieces (dropped %zu triangles in pieces under %g of the "
                                 "largest; --wall-pieces 0 keeps them)\n",
                         pieces.kept, pieces.pieces, pieces.dropped_triangles, double(wall_pieces));
        return 0;
    }
}

PATHLET_COMMAND("trace", "trace dense pathlines (and the wall) from a velocity volume (.vtk, .vti, .h5)", run);

}  // namespace
}  // namespace pathlet::cli
