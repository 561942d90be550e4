// pathlet trace FIELD -o OUT: dense pathlines (and optionally the wall) from a velocity volume.
#include "commands.hpp"
#include "data_outputs.hpp"
#include "common/fraction_progress.hpp"
#include "io/units.hpp"
#include "trace/field_readers.hpp"
#include "trace/marching_cubes.hpp"
#include "trace/tracer.hpp"

#include <algorithm>
#include <optional>
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

int run(const std::vector<std::string>& argv) {
    Args a("trace", "Traces dense pathlines through a velocity volume (study report I.b): seeds until every vessel\n"
                    "voxel is crossed by a line, RK4 backward and forward in time from each seed, drops lines that\n"
                    "are too short or run alongside accepted ones, smooths with a binomial filter, resamples.\n"
                    "Inputs: VTK legacy STRUCTURED_POINTS .vtk, VTK XML .vti, 4DFlowNet .h5 (u, v, w, mask, dx).\n"
                    "The vessel is the file's mask (>= 0.5), or SCALARS > --mask-threshold, or the whole grid.\n"
                    "The result does not depend on --threads. Exit status: 0 ok, 1 bad data, 2 bad usage.");
    std::string field_file, pulsatile, units;
    DataOutputs out;
    std::optional<float> mask_threshold;
    float vscale = 1.0f, wall_pieces = 0.01f;
    long max_lines = 0, seed = 1;
    bool periodic = false, forward_only = false;
    trace::TraceOptions o;  // its defaults are the options' defaults, but for a longer release window
    o.time_end = 10.0f;
    a.positional("FIELD", field_file, "velocity volume (.vtk, .vti, .h5)");
    out.declare(a, "also write the vessel wall (marching cubes of the mask) as .glb/.gltf/.stl/.obj");
    a.option("wall-pieces", wall_pieces, "SHARE",
             "drop wall pieces with fewer triangles than SHARE of the largest (a thresholded scan's noise specks); 0 keeps all")
        .option("mask-threshold", mask_threshold, "X", "vessel = scalars > X (e.g. 175 for carotid.vtk)")
        .option("velocity-scale", vscale, "S", "multiply velocities (e.g. to convert units to world units/s)")
        .option("units", units, "LENGTH[,VELOCITY]",
                "units written with the pathlines where the field does not say them (the .h5 layout does: mm, mm/s)")
        .option("step", o.step, "VOXELS", "RK4 step length in voxels")
        .option("max-dt", o.max_dt, "SECONDS", "largest time step")
        .option("duration", o.time_end, "SECONDS", "release window: seeds released over [0, duration); lines clipped to it")
        .option("line-time", o.max_line_time, "SECONDS", "longest duration of one line")
        .option("min-length", o.min_length, "L", "drop lines shorter than L (world units)")
        .option("min-distance", o.min_distance, "D", "drop lines running within D of accepted lines (0: off)")
        .option("close-fraction", o.close_fraction, "F", "... when this fraction of their points is that close")
        .option("smooth", o.smooth_passes, "N", "binomial smoothing passes")
        .option("resample", o.resample_step, "L", "distance between output points (0: one voxel)")
        .option("pulsatile", pulsatile, "PERIOD,PEAK", "modulate a steady field with the systole/diastole waveform")
        .flag("periodic", periodic, "frames repeat over the cycle (time-resolved input)")
        .flag("forward-only", forward_only, "integrate forward from the seed only")
        .option("max-lines", max_lines, "N", "stop after N lines (0: no limit)")
        .option("seed", seed, "N", "seeding hash seed")
        .option("threads", o.threads, "N", "worker threads (0: all cores)")
        .example("pathlet trace carotid.vtk --mask-threshold 175 -o carotid.vtp --wall carotid.glb",
                 "steady carotid field, vessel from the scalar volume")
        .example("pathlet trace example_data_HR.h5 -o arch.vtp --pulsatile 0.8,2.85 --min-length 10 --min-distance 0.6",
                 "4DFlowNet aortic arch made pulsatile, sparser lines")
        .example("pathlet trace flow.vti -o flow.pathlet --periodic --duration 3", "time-resolved .vti frames, cached output");
    if (!a.parse(argv)) return 0;
    out.check();  // before minutes of tracing
    o.periodic = periodic;
    o.bidirectional = !forward_only;
    o.max_lines = size_t(std::max(0L, max_lines));
    o.seed = uint64_t(seed);
    if (!pulsatile.empty()) o.pulsatile = parse_pulsatile(pulsatile);
    if (!(o.step > 0) || !(o.max_dt > 0) || !(o.time_end > 0) || !(o.max_line_time > 0) || o.smooth_passes < 0 || o.threads < 0)
        throw UsageError("--step, --max-dt, --duration, --line-time must be > 0; --smooth, --threads >= 0");
    if (!(wall_pieces >= 0.0f && wall_pieces <= 1.0f)) throw UsageError("--wall-pieces must lie in 0..1");
    try {
        Units probe;
        io::apply_units_option(probe, units);  // a bad spec is a usage error before minutes of tracing
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }

    FractionProgress progress("trace");
    trace::VelocityField field = trace::load_velocity_field(field_file);
    if (mask_threshold) field.mask_from_scalars(*mask_threshold);
    if (vscale != 1.0f) {
        for (auto& f : field.frames)
            for (auto& v : f) v *= vscale;
        field.units.velocity = "";  // scaled into something only the user knows: --units says it
    }
    trace::TraceStats st;
    Pathlines lines = trace::trace_pathlines(field, o, progress.callback(), &st);
    io::apply_units_option(lines.units, units);
    trace::PieceStats pieces;
    if (!out.wall.empty()) out.write_wall(trace::vessel_wall(field, wall_pieces, &pieces, progress.callback()));
    out.write_lines(lines);
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

PATHLET_COMMAND("trace", "trace dense pathlines (and the wall) from a velocity volume (.vtk, .vti, .h5)", run);

}  // namespace
}  // namespace pathlet::cli
