// Synthetic aortic-arch flow phantom, generated deterministically: a tube around the arch
// centreline (centerline.hpp) voxelised into a mask, a steady velocity field with a
// parabolic axial profile, helical secondary flow in the arch and an optional saccular
// aneurysm with a vortex; made pulsatile by the tracer's waveform, traced with the same
// tracer as real data, and walled with the same marching cubes. World units mm, time s.
#pragma once

#include "centerline.hpp"
#include "trace/progress.hpp"
#include "trace/tracer.hpp"
#include "trace/velocity_field.hpp"

#include <pathlet/scene.hpp>

#include <string>

namespace pathlet::phantom {

struct PhantomOptions {
    std::string preset = "study";
    ArchShape shape;
    float voxel = 1.0f;          // mm, grid spacing
    float mean_speed = 150.0f;   // mm/s, cycle-mean axial speed at the root
    bool aneurysm = true;        // saccular bulge on the descending aorta, with a vortex
    float aneurysm_radius = 12.0f;  // mm
    trace::TraceOptions trace;   // seeding, filtering, time window, pulsatile waveform
};

// "study": sized like the study data set (about 3169 lines, 644k points, 18 s).
// "small": a few hundred lines for tests and quick looks.
// "NAME:density=N": N times the lines of NAME (more seeds, the same vessel and time span;
// TraceOptions::density), N in 1..kMaxDensity.
// Throws std::invalid_argument for other names.
constexpr int kMaxDensity = 64;
PhantomOptions phantom_preset(const std::string& spec);

// The voxelised phantom: steady velocity shape (mm/s) and a soft mask whose 0.5
// iso-surface is the lumen wall.
trace::VelocityField make_phantom_field(const PhantomOptions& opts);

Scene make_phantom(const PhantomOptions& opts, const trace::Progress& progress = {}, trace::TraceStats* stats = nullptr);

// Cache file for a preset's pathlines (.pathlet; the wall is the same path with .glb):
// $XDG_CACHE_HOME/pathlet/ or ~/.cache/pathlet/, named with the generator version.
std::string phantom_cache_path(const std::string& spec);
// Loads the cached phantom, or generates it and writes the cache (atomically) first.
Scene load_or_make_phantom(const std::string& spec, const trace::Progress& progress = {});

}  // namespace pathlet::phantom
