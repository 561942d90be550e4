// The module's measures: pathlet.bench (the experiment runner the command uses), quality (AO
// against ray tracing, transparency, fidelity against a reference graph) and the AO measure's
// options, by the same functions as `pathlet bench` and `pathlet quality`.
#include "gl_thread.hpp"
#include "module_common.hpp"

#include "ao_options.hpp"
#include "bench/experiment.hpp"
#include "bench/report.hpp"
#include "bench/run_experiment.hpp"
#include "common/scene_source.hpp"
#include "image_io.hpp"
#include "measure.hpp"
#include "reference.hpp"
#include "renderer.hpp"
#include "transparency.hpp"
#include "util/output_check.hpp"
#include <pathlet/text.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>
#include <variant>

namespace pathlet::python {
namespace {

// ---- experiments and quality ----------------------------------------------------------------

struct BenchArgs {
    std::string experiment;        // a file, or
    std::string experiment_json;   // an experiment as JSON text (pathlet.bench)
    std::string origin = "pathlet.bench()";
    std::vector<std::string> sizes, sets;
    std::string time, timing = "auto", out, shard, command = "python: pathlet";
    int frames = -1, warmup = -1;
    bool images = false;
};

py::object run_bench(const BenchArgs& a, const std::optional<SceneRef>& scene) {
    cli::bench::Experiment e = a.experiment.empty()
                              ? cli::bench::parse_experiment(json::parse(a.experiment_json), a.origin)
                              : cli::bench::load_experiment(a.experiment);
    if (!a.sizes.empty()) e.sizes = a.sizes;
    if (!a.time.empty()) e.time = a.time;
    if (a.frames >= 0) e.frames = a.frames;
    if (a.warmup >= 0) e.warmup = a.warmup;
    e.sets.insert(e.sets.end(), a.sets.begin(), a.sets.end());
    if (e.frames < 1) throw std::invalid_argument("frames must be >= 1");
    for (const auto& s : e.sizes) parse_size(s);
    if (!e.time.empty()) parse_time_range(e.time);
    if (scene) e.data.clear();  // a scene given replaces the experiment's data sets, as --data does
    cli::bench::ExperimentSettings how;
    how.timing = parse_timing_backend(a.timing);
    if (!a.shard.empty()) how.shard = cli::parse_shard(a.shard);
    how.command = a.command;
    how.graphs = cli::bench::graph_info(e, a.experiment);
    if (!a.out.empty()) check_output_dir(a.out, "experiment results (out)");
    if (a.images && !a.out.empty()) how.image_dir = a.out;
    cli::bench::ExperimentHooks hooks;
    hooks.load_data = [&](size_t d) {
        if (scene) return Scene(**scene);
        if (e.data.empty()) return load_scene(SceneSource{}, true);
        return cli::bench::load_data_set(e.data[d]);
    };
    hooks.on_report = [&](const json& report, const cli::bench::RunDone*) {
        if (!a.out.empty()) cli::bench::write_report_dir(a.out, report);
    };
    json report;
    {
        py::gil_scoped_release nogil;
        report = GlThread::get().call([&](Runtime& rt) { return cli::bench::run_experiment(rt, e, how, hooks); });
    }
    return from_json(report);
}

// Python's keyword arguments of the AO measure, by the table the command declares its options
// from (quality/ao_options.hpp): an unknown name is a TypeError naming the known ones.
void apply_ao_options(quality::QualityOptions& q, const py::dict& options) {
    std::vector<std::string> known;
    for (const auto& o : quality::ao_options()) known.push_back(o.name);
    for (const auto& [key, value] : options) {
        const std::string name = py::str(key);
        const auto it = std::find_if(quality::ao_options().begin(), quality::ao_options().end(),
                                     [&](const quality::AoOption& o) { return name == o.name; });
        if (it == quality::ao_options().end())
            throw py::type_error("quality() got an unexpected keyword argument '" + name + "'" +
                                 text::did_you_mean(name, known) + "; its AO options: " + text::join(known));
        std::visit(
            [&](auto field) {
                using T = std::remove_reference_t<decltype(q.*field)>;
                try {
                    q.*field = value.cast<T>();
                } catch (const py::cast_error&) {
                    throw py::type_error("quality(): " + name + " expects " +
                                         (std::is_same_v<T, bool> ? "a bool" : std::is_same_v<T, int> ? "an int" : "a number") +
                                         ", got " + std::string(py::str(py::repr(value))));
                }
            },
            it->field);
    }
}

py::list ao_option_list() {
    const quality::QualityOptions defaults;
    py::list out;
    for (const auto& o : quality::ao_options()) {
        py::dict d;
        d["name"] = o.name;
        d["doc"] = o.doc;
        std::visit([&](auto field) { d["default"] = defaults.*field; }, o.field);
        out.append(d);
    }
    return out;
}

py::dict run_quality(const std::string& graph, const std::vector<std::string>& sets, const SceneRef& scene,
                     const std::string& time, const std::string& size, const py::dict& options,
                     const std::string& work_dir) {
    quality::QualityOptions q;
    apply_ao_options(q, options);
    q.graph_path = graph;
    q.sets = sets;
    q.size = parse_size(size);
    if (!time.empty()) q.time = parse_time_range(time);
    q.work_dir = work_dir;
    quality::check_quality_options(q);  // the command's limits
    quality::QualityResult r;
    std::vector<uint8_t> picture;
    {
        py::gil_scoped_release nogil;
        r = GlThread::get().call([&](Runtime& rt) { return quality::measure_quality(rt, *scene, q); });
        if (r.not_measured.empty()) picture = to_rgba8(quality::error_image(r.last, r.error.abs_error));
    }
    py::dict d;
    d["graph"] = r.graph;
    if (!r.not_measured.empty()) {
        d["not_measured"] = r.not_measured;
        return d;
    }
    const py::ssize_t h = r.last.height, w = r.last.width;
    d["frames"] = r.frames;
    d["times"] = py::make_tuple(r.first_time, r.last_time);
    d["flicker"] = r.flicker.ao_flicker;
    d["stable_pixels"] = r.flicker.stable_pixels;
    d["geometry_change"] = r.flicker.geometry_change;
    if (q.flicker_rays > 0) {
        d["reference_change"] = r.reference_flicker.reference_change;
        d["flicker_excess"] = r.reference_flicker.excess;
    }
    d["mae"] = r.error.mae;
    d["correlation"] = r.error.correlation;
    d["pixels"] = r.error.pixels;
    d["rays"] = q.rays;
    d["reach"] = r.reach;
    d["segments"] = r.segments;
    d["error"] = to_numpy(std::move(r.error.abs_error), {h, w});
    d["error_image"] = to_numpy(std::move(picture), {h, w, 4});
    d["ao"] = to_numpy(std::move(r.last.ao), {h, w});
    d["reference"] = to_numpy(std::move(r.reference), {h, w});
    d["line_id"] = to_numpy(std::move(r.last.line_id), {h, w});
    return d;
}

// quality(..., reference=...): fidelity against a reference graph.
py::dict run_reference(const std::string& graph, const std::vector<std::string>& sets, const std::string& reference,
                       const std::vector<std::string>& reference_sets, const SceneRef& scene, const std::string& time,
                       const std::string& size, const std::string& out_dir, std::optional<double> ppd) {
    quality::ReferenceOptions o;
    if (ppd) {  // as the command's --ppd
        if (!(*ppd > 0.0) || !std::isfinite(*ppd))
            throw py::value_error("ppd must be a positive number of pixels per degree (got " + std::to_string(*ppd) + ")");
        o.ppd = *ppd;
    }
    o.graph_path = graph;
    o.reference_path = reference;
    o.sets = sets;
    o.reference_sets = reference_sets;
    o.size = parse_size(size);
    if (!time.empty()) o.time = parse_time_range(time);
    o.out_dir = out_dir;
    quality::ReferenceResult r;
    {
        py::gil_scoped_release nogil;
        r = GlThread::get().call([&](Runtime& rt) { return quality::measure_against_reference(rt, *scene, o); });
    }
    auto metrics = [](const quality::ImageMetrics& m) {
        py::dict d;
        d["ssim"] = m.ssim, d["psnr"] = m.psnr, d["rmse"] = m.rmse, d["share_over"] = m.share_over;
        d["flip"] = m.flip, d["flip_all"] = m.flip_all;
        d["pixels"] = m.pixels;
        return d;
    };
    py::dict d = metrics(r.metrics);
    d["graph"] = r.graph;
    d["reference"] = r.reference;
    d["frames"] = r.frames;
    d["times"] = py::make_tuple(r.first_time, r.last_time);
    if (r.flicker) {
        d["flicker_excess"] = r.flicker->excess;
        d["flicker"] = r.flicker->test_change;
        d["reference_change"] = r.flicker->reference_change;
    }
    py::list frames;
    for (const quality::ImageMetrics& m : r.per_frame) frames.append(metrics(m));
    d["per_frame"] = frames;
    d["images"] = r.images;
    d["incomplete_frames"] = r.incomplete_frames;  // of the tested graph (a reference with any is refused)
    return d;
}

py::dict run_transparency(const std::string& graph, const std::vector<std::string>& sets, const SceneRef& scene,
                          const std::string& time, const std::string& size, int repeat, double focus_share,
                          double visible) {
    quality::TransparencyOptions t;
    t.graph_path = graph;
    t.sets = sets;
    t.size = parse_size(size);
    if (!time.empty()) t.time = parse_time_range(time);
    t.repeat = repeat;
    t.focus_share = focus_share;
    t.threshold = visible;
    quality::check_transparency_options(t);  // the command's limits
    quality::TransparencyResult r;
    {
        py::gil_scoped_release nogil;
        r = GlThread::get().call([&](Runtime& rt) { return quality::measure_transparency(rt, *scene, t); });
    }
    py::dict d;
    d["graph"] = r.graph;
    if (!r.not_measured.empty()) {
        d["not_measured"] = r.not_measured;
        return d;
    }
    d["frames"] = r.frames;
    d["times"] = py::make_tuple(r.first_time, r.last_time);
    d["focus_visibility"] = r.focus_visibility;
    d["focus_unoccluded"] = r.focus_unoccluded;
    d["focus_ink_share"] = r.focus_ink_share;
    d["context_coverage"] = r.context_coverage;
    d["alpha_change_mean"] = r.alpha_change_mean;
    d["alpha_change_p95"] = r.alpha_change_p95;
    d["alpha_change_max"] = r.alpha_change_max;
    d["max_alpha_change_per_frame"] = r.max_alpha_change_per_frame;
    d["overflow"] = r.overflow;
    d["pixel_coverage"] = r.pixel_coverage;
    d["focus_speed"] = r.focus_speed;
    d["fragments"] = r.fragments;
    d["located"] = r.located;
    return d;
}

}  // namespace

void bind_measures(py::module_& m) {
    py::class_<BenchArgs>(m, "BenchArgs")
        .def(py::init<>())
        .def_readwrite("experiment", &BenchArgs::experiment)
        .def_readwrite("experiment_json", &BenchArgs::experiment_json)
        .def_readwrite("origin", &BenchArgs::origin)
        .def_readwrite("sizes", &BenchArgs::sizes)
        .def_readwrite("sets", &BenchArgs::sets)
        .def_readwrite("time", &BenchArgs::time)
        .def_readwrite("timing", &BenchArgs::timing)
        .def_readwrite("out", &BenchArgs::out)
        .def_readwrite("shard", &BenchArgs::shard)
        .def_readwrite("command", &BenchArgs::command)
        .def_readwrite("frames", &BenchArgs::frames)
        .def_readwrite("warmup", &BenchArgs::warmup)
        .def_readwrite("images", &BenchArgs::images);
    m.def("bench", [](const BenchArgs& a, const std::optional<std::shared_ptr<Scene>>& s) {
        return run_bench(a, s ? std::optional<SceneRef>(*s) : std::nullopt);
    });
    m.def("quality", [](const std::string& graph, const std::vector<std::string>& sets, const std::shared_ptr<Scene>& s,
                        const std::string& time, const std::string& size, const py::dict& options,
                        const std::string& work_dir) { return run_quality(graph, sets, s, time, size, options, work_dir); });
    // The AO measure's options (name, default, doc), as `pathlet quality --help` lists them.
    m.def("quality_options", &ao_option_list);
    m.def("quality_reference", &run_reference);
    m.def("transparency", [](const std::string& graph, const std::vector<std::string>& sets, const std::shared_ptr<Scene>& s,
                             const std::string& time, const std::string& size, int repeat, double focus_share,
                             double visible) {
        return run_transparency(graph, sets, s, time, size, repeat, focus_share, visible);
    });
}

}  // namespace pathlet::python
