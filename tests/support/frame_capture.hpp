// Render one frame of a graph and read its GPU resources back as Images, for tests that look
// at intermediate maps (G-buffer colour, depth, line ids) rather than only at captured files.
#pragma once

#include "camera.hpp"
#include "image_io.hpp"
#include "renderer.hpp"
#include "runtime.hpp"

#include <map>
#include <string>
#include <vector>

namespace pathlet {

// Everything a test looks at after one frame: textures by resource name, pass stats.
struct Frame {
    std::map<std::string, Image> tex;
    std::map<std::string, double> stats;  // "<stat>" of every pass (last pass wins on clashes)
    Camera camera;                        // the framing camera (when no camera path was given)
    const Image& operator[](const std::string& n) const { return tex.at(n); }
};

// One runtime (GL context + plugins from the default search path and `plugin_dirs`) per
// test binary; leaked on purpose (no GL teardown order at exit).
Runtime& test_runtime(const std::vector<std::string>& plugin_dirs = {});

// Reads a texture the way it is stored: depth as one float, r32i as one float per pixel,
// r32f as one channel, everything else as RGBA. Rows top-down like Image.
Image read_resource(const Texture& t);

// Renders `opt` (time start only, no files) and reads the named resources.
Frame render_frame(Runtime& rt, const Scene& scene, RenderOptions opt, const std::vector<std::string>& names);

// The built-in small phantom (lines and wall, 0..4 s), made once per process.
const Scene& small_phantom_scene();

// The test bundle: 40 helices around the x axis (4 rings, speeds varying per line and in time)
// and one isolated, gently waving line beside it; times 0..10 s, 101 points per line.
const Scene& helix_bundle_scene();

// A per-process scratch folder "<tmp>/<prefix>_<pid>", removed when the test binary ends.
const std::string& test_scratch_dir(const std::string& prefix);

// Two straight pathlets, times 0..10 s (201 points each): a fast one, x = -15 + 4t on y = 0
// (40 units long), and a slow one, x = t on y = 4 (10 units long). Units mm, s, mm/s (like
// the helix bundle's).
const Scene& two_speed_lines_scene();
// Writes a camera path that looks down -z at (5, 2, 0) from 60 units with fovy 20 degrees and
// +y up, so data x runs to the right; returns `path`.
std::string write_square_on_camera(const std::string& path);
// Pixels per world unit at z = 0 for that camera and an image `height` pixels high.
float square_on_pixels_per_unit(int height);

}  // namespace pathlet
