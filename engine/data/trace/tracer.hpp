// Dense pathline tracing in a velocity volume (study report I.b): seeds are placed until
// every vessel voxel is crossed by a line, each seed is integrated with RK4 backward and
// forward in time, too-short lines and lines running alongside accepted ones are dropped,
// the rest are smoothed with a 1-D binomial filter and resampled.
//
// Determinism: seed order, seed jitter and release times come from a hash of the voxel
// index and `seed`; candidates are traced in parallel in fixed-size batches but accepted
// or rejected one by one in seed order, so the result does not depend on `threads`.
#pragma once

#include "progress.hpp"
#include "pulsatile.hpp"
#include "velocity_field.hpp"

#include <optional>

namespace pathlet::trace {

struct TraceOptions {
    // Integration
    float step = 0.25f;            // RK4 step length, in units of the smallest voxel spacing
    float max_dt = 0.02f;          // s; caps the step so time variation (frames, pulse) is resolved
    float min_speed_fraction = 1e-3f;  // stop where |v| < this * the field's max speed
    int max_steps = 20000;         // per direction
    float max_line_time = 4.0f;    // s; total duration of one line (half budget backward)
    bool bidirectional = true;     // integrate backward from the seed too (longer lines)
    bool periodic = false;         // frames repeat over field.cycle()
    std::optional<Pulsatile> pulsatile;  // modulate (typically a steady) field

    // Seeding: release (seed) times spread uniformly over [time_begin, time_end); lines
    // are clipped to that window so a time window of the animation shows a moving population.
    float time_begin = 0.0f;
    float time_end = 1.0f;
    uint64_t seed = 1;
    float seed_jitter = 0.5f;      // fraction of a voxel a seed may move from the voxel centre

    // Filtering and output
    float min_length = 0.0f;       // world units; shorter lines are dropped
    float min_distance = 0.0f;     // world units; 0 disables the closeness test
    float close_fraction = 0.8f;   // drop a line when this fraction of its points are within min_distance of accepted lines
    int smooth_passes = 2;         // binomial [1 2 1] passes
    float resample_step = 0.0f;    // world units between output points; 0 = smallest voxel spacing
    size_t max_lines = 0;          // 0 = no limit
    // Density: lines per accepted seed. Above 1, each accepted line gets density - 1 companions
    // seeded in its voxel at release times of their own (after every accepted line, in blocks:
    // the first block is the data set at density 1), kept without the closeness test: the same
    // vessel and time span, exactly density times the lines.
    int density = 1;

    // Execution
    int threads = 0;               // 0 = all hardware threads
    int batch = 256;               // candidates traced per parallel batch (part of the result!)
};

struct TraceStats {
    size_t vessel_voxels = 0;
    size_t covered_voxels = 0;     // crossed by an accepted line
    size_t candidates = 0;         // seeds traced
    size_t rejected_short = 0;
    size_t rejected_close = 0;
    size_t skipped_covered = 0;    // seed voxel already crossed by an earlier line of its batch
    uint64_t particle_steps = 0;   // RK4 steps taken over all candidates
};

// Throws DataError (naming field.source) when the field is unusable.
Pathlines trace_pathlines(const VelocityField& field, const TraceOptions& opts, const Progress& progress = {},
                          TraceStats* stats = nullptr);

// Integrates one pathline from (seed, t0) with the tracer's stopping rules; no filtering,
// smoothing or resampling. Exposed for tests and benchmarks.
struct TracedLine;
class FlowSampler;
TracedLine integrate_line(const FlowSampler& flow, glm::vec3 seed, float t0, const TraceOptions& opts,
                          float min_speed, uint64_t* steps = nullptr);

}  // namespace pathlet::trace
