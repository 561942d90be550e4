// Option blocks several commands share, declared once: a struct of typed values and the
// declaration that binds them, so --plugin-dir, the data options, --set, --size, --camera and
// --timing read and document alike in every command that has them.
#pragma once

#include "args.hpp"

#include <pathlet/scene.hpp>

#include "common/scene_source.hpp"
#include "io/pathline_io.hpp"
#include "profiler/profiler.hpp"
#include "runtime.hpp"

#include <string>
#include <vector>

namespace pathlet::cli {

// --plugin-dir DIR (repeatable): folders of pass plugins searched before PATHLET_PLUGIN_PATH
// and the built-in folder; --trust-graph-plugins: load the plugin folders graph files name for
// this run, trusted or not (plugin_trust.hpp).
struct PluginOptions {
    std::vector<std::string> dirs;
    bool trust_graph_plugins = false;
    void declare(Args& a, bool graph_files = true);
    void load(Runtime& rt) const;  // the search path's plugins, and the trust setting
};

// How pathline files are read: --time-array, --velocity-array, --time-step, --units,
// --streamlines, --pseudo-time (render, bench, view, quality and info).
struct ArrayOptions {
    std::string time_array, velocity_array;
    double time_step = 0;
    std::string units;
    bool streamlines = false, pseudo_time = false;
    void declare(Args& a);
    io::LoadOptions load_options() const;  // UsageError for a negative --time-step or malformed --units
};

// The data a command draws: --data FILE (pathlines or tracts), --mesh FILE (vessel wall),
// --phantom PRESET (the default when --data is not given), and the array options.
struct SceneOptions {
    std::string data, mesh;
    Given<std::string> phantom{"study"};
    ArrayOptions arrays;
    void declare(Args& a);
    bool given() const { return !data.empty() || !mesh.empty() || phantom.given; }
    // What the options name (UsageError for a malformed --units or --time-step).
    SceneSource source() const;
    // Loads it (common/scene_source.hpp's load_scene): a one-line summary, repair warnings on
    // stderr, a DataError when no line is left to draw.
    Scene load(bool quiet) const { return load_scene(source(), quiet); }
};

// A time the user gave that reaches outside the data's time span would render frames with
// nothing in them: InputError (exit 2) naming what was given and the data's span, unless
// `allow_empty` (--allow-empty-frames). Data without time takes any time.
void check_time_in_data(const TimeRange& t, const std::string& given, const Scene& scene, bool allow_empty);


// --set NAME=VALUE (repeatable): a graph variable or a pass parameter.
void declare_sets(Args& a, std::vector<std::string>& sets);
// --size WxH, with what the size is of ("output size in pixels").
void declare_size(Args& a, glm::ivec2& size, const std::string& what);
// --camera FILE: a camera path (render --camera's format).
void declare_camera(Args& a, std::string& file);
// --timing auto|gpu|finish|cpu: how passes are timed.
void declare_timing(Args& a, TimingBackend& timing);

}  // namespace pathlet::cli
