// _pathlet: the C++ side of `import pathlet`. Thin on purpose: data loading, graph overrides,
// rendering, experiments and quality measures are the same functions the `pathlet` command
// calls (load_scene, Runtime::load_graph/apply_overrides, render(), cli::bench::run_experiment,
// quality::measure_quality). What is here: NumPy in and out, errors as Python exceptions, and
// the one GL thread (gl_thread.hpp). The friendly API is pathlet/__init__.py.
#include "gl_thread.hpp"

#include "bench/experiment.hpp"
#include "bench/run_experiment.hpp"
#include "bench/report.hpp"
#include "build_info.hpp"
#include "common/scene_source.hpp"
#include "executor.hpp"
#include "formats.hpp"
#include "graph/hook_params.hpp"
#include "image_io.hpp"
#include "io/mesh_io.hpp"
#include "io/raw_polylines.hpp"
#include "io/units.hpp"
#include "measure.hpp"
#include "reference.hpp"
#include "transparency.hpp"
#include "renderer.hpp"
#include "util/output_check.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace py = pybind11;
using nlohmann::json;

namespace pathlet::python {
namespace {

using SceneRef = std::shared_ptr<const Scene>;

// ---- errors ------------------------------------------------------------------------------

// Python's json module turns our JSON text into dicts (no converter to maintain).
py::object from_json(const json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

void raise_graph_error(const GraphError& e) {
    py::list diags;
    for (const auto& d : e.diagnostics) {
        py::dict x;
        x["file"] = d.file;
        x["pointer"] = d.pointer;
        x["message"] = d.message;
        x["line"] = d.line;
        x["column"] = d.column;
        x["text"] = d.str();
        diags.append(x);
    }
    py::object cls = py::module_::import("pathlet._errors").attr("GraphError");
    std::string text;
    for (const auto& d : e.diagnostics) text += (text.empty() ? "" : "\n") + d.str();
    PyErr_SetObject(cls.ptr(), cls(text, diags).ptr());
}

void raise_as(const char* name, const std::exception& e) {
    py::object cls = py::module_::import("pathlet._errors").attr(name);
    PyErr_SetString(cls.ptr(), e.what());
}

void translate(std::exception_ptr p) {
    try {
        if (p) std::rethrow_exception(p);
    } catch (const GraphError& e) {
        raise_graph_error(e);
    } catch (const GraphNotFound& e) {  // a graph name that names nothing: one problem, of no file
        py::dict d;
        d["file"] = "", d["pointer"] = "", d["message"] = e.what(), d["line"] = 0, d["column"] = 0, d["text"] = e.what();
        py::object cls = py::module_::import("pathlet._errors").attr("GraphError");
        PyErr_SetObject(cls.ptr(), cls(e.what(), py::make_tuple(d)).ptr());
    } catch (const ClosedError& e) {
        raise_as("ClosedError", e);
    } catch (const DataError& e) {
        raise_as("DataError", e);
    } catch (const PassError& e) {
        raise_as("PassError", e);
    } catch (const GlError& e) {
        raise_as("GlError", e);
    }
}

// ---- scenes --------------------------------------------------------------------------------

SceneRef load_scene_source(const SceneSource& src) {
    py::gil_scoped_release nogil;  // CPU work (a phantom may be generated): other threads go on
    return std::make_shared<Scene>(load_scene(src, true));
}

template <class T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;

void check_shape(const py::array& a, const char* name, std::vector<py::ssize_t> shape) {
    bool ok = a.ndim() == py::ssize_t(shape.size());
    for (size_t i = 0; ok && i < shape.size(); ++i) ok = shape[i] < 0 || a.shape(py::ssize_t(i)) == shape[i];
    if (!ok) {
        std::string want;
        for (size_t i = 0; i < shape.size(); ++i) want += (i ? ", " : "") + (shape[i] < 0 ? std::string("n") : std::to_string(shape[i]));
        std::string got;
        for (py::ssize_t i = 0; i < a.ndim(); ++i) got += (i ? ", " : "") + std::to_string(a.shape(i));
        throw std::invalid_argument(std::string(name) + ": expected shape (" + want + "), got (" + got + ")");
    }
}

// Pathlines from NumPy through the importers' own repair step (NaN points dropped, time
// ordered, velocity from differences when absent), with the warnings it gives.
py::tuple scene_from_arrays(const Array<float>& points, const Array<int64_t>& offsets, const Array<float>& times,
                            const std::optional<Array<float>>& velocity, const std::string& source,
                            const std::string& units) {
    check_shape(points, "points", {-1, 3});
    const size_t n = size_t(points.shape(0));
    check_shape(times, "times", {py::ssize_t(n)});
    check_shape(offsets, "offsets", {-1});
    if (velocity) check_shape(*velocity, "velocity", {py::ssize_t(n), 3});
    const int64_t* off = offsets.data();
    const size_t lines = offsets.size() > 0 ? size_t(offsets.size()) - 1 : 0;
    if (offsets.size() < 2 || off[0] != 0 || off[lines] != int64_t(n))
        throw std::invalid_argument("offsets: expected the start of every line and then the point count (" +
                                    std::to_string(n) + "): [0, ..., " + std::to_string(n) + "]");
    for (size_t i = 0; i < lines; ++i)
        if (off[i + 1] < off[i])
            throw std::invalid_argument("offsets[" + std::to_string(i + 1) + "] = " + std::to_string(off[i + 1]) +
                                        " is smaller than offsets[" + std::to_string(i) + "] = " + std::to_string(off[i]));
    auto scene = std::make_shared<Scene>();
    Pathlines& pl = scene->lines;
    const float* p = points.data();
    pl.position.resize(n);
    pl.time.assign(times.data(), times.data() + n);
    for (size_t i = 0; i < n; ++i) pl.position[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    if (velocity) {
        pl.velocity.resize(n);
        const float* v = velocity->data();
        for (size_t i = 0; i < n; ++i) pl.velocity[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    }
    for (size_t i = 0; i < lines; ++i) pl.lines.push_back({uint32_t(off[i]), uint32_t(off[i + 1] - off[i])});
    io::apply_units_option(pl.units, units);  // "" keeps them unknown: the legend says "speed"
    io::LoadReport rep;
    io::repair_pathlines(pl, rep, source);
    pl.check_consistent(source);
    scene->source = source;
    return py::make_tuple(SceneRef(scene), rep.warnings);
}

SceneRef with_wall(const SceneRef& s, const Mesh& mesh) {
    auto out = std::make_shared<Scene>(*s);
    out->mesh = mesh;
    return out;
}

Mesh mesh_from_arrays(const Array<float>& vertices, const Array<int64_t>& triangles) {
    check_shape(vertices, "wall vertices", {-1, 3});
    check_shape(triangles, "wall triangles", {-1, 3});
    Mesh m;
    const float* v = vertices.data();
    for (py::ssize_t i = 0; i < vertices.shape(0); ++i) m.position.push_back({v[3 * i], v[3 * i + 1], v[3 * i + 2]});
    const int64_t* t = triangles.data();
    for (py::ssize_t i = 0; i < triangles.size(); ++i) {
        if (t[i] < 0 || t[i] >= vertices.shape(0))
            throw std::invalid_argument("wall triangles: index " + std::to_string(t[i]) + " at [" + std::to_string(i / 3) +
                                        ", " + std::to_string(i % 3) + "] is not one of the " +
                                        std::to_string(vertices.shape(0)) + " vertices");
        m.index.push_back(uint32_t(t[i]));
    }
    m.compute_normals();
    return m;
}

template <class T>
py::array to_numpy(std::vector<T>&& v, std::vector<py::ssize_t> shape) {
    auto* heap = new std::vector<T>(std::move(v));
    py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    return py::array_t<T>(shape, heap->data(), owner);
}

py::dict scene_arrays(const Scene& s) {
    const Pathlines& l = s.lines;
    const size_t n = l.point_count();
    std::vector<float> pos(n * 3), vel(n * 3);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            pos[i * 3 + c] = l.position[i][c];
            vel[i * 3 + c] = i < l.velocity.size() ? l.velocity[i][c] : 0.0f;
        }
    std::vector<int64_t> off{0};
    for (const auto& r : l.lines) off.push_back(int64_t(r.first) + r.count);
    py::dict d;
    d["points"] = to_numpy(std::move(pos), {py::ssize_t(n), 3});
    d["offsets"] = to_numpy(std::move(off), {py::ssize_t(l.line_count() + 1)});
    d["times"] = to_numpy(std::vector<float>(l.time), {py::ssize_t(n)});
    d["velocity"] = to_numpy(std::move(vel), {py::ssize_t(n), 3});
    return d;
}

// ---- graphs ---------------------------------------------------------------------------------

json decl_json(const ParamDecl& d) {
    json j = {{"type", to_string(d.type)}, {"default", d.def}, {"doc", d.doc}};
    if (std::isfinite(d.min)) j["min"] = d.min;
    if (std::isfinite(d.max)) j["max"] = d.max;
    if (!d.choices.empty()) j["choices"] = d.choices;
    return j;
}

// What a graph declares, with the overrides applied (GraphError when one is wrong): the
// variables and every pass's parameters with their current values and declarations.
json describe_graph(Runtime& rt, const std::string& path, const std::vector<std::string>& sets) {
    const GraphFile g = rt.load_graph(path, sets);
    json vars = json::object();
    for (const auto& v : g.variables) {
        json d = decl_json(v.decl);
        d["value"] = v.value;
        vars[v.name] = d;
    }
    json passes = json::array();
    for (const auto& p : g.passes) {
        json params = json::object();
        auto value_of = [&](const ParamDecl& d, json* variable) {
            json value = p.params.contains(d.name) ? p.params[d.name] : d.def;
            if (value.is_string() && !value.get<std::string>().empty() && value.get<std::string>()[0] == '$') {
                if (variable) *variable = value.get<std::string>().substr(1);
                const std::string name = value.get<std::string>().substr(1);
                for (const auto& v : g.variables)
                    if (v.name == name) value = v.value;
            }
            return value;
        };
        // With the parameters its hooks declare (resolved when the graph loaded).
        std::shared_ptr<const PassTypeInfo> type = p.instance_type;
        if (type)
            for (const auto& d : type->params) {
                json x = decl_json(d);
                json variable;
                x["value"] = value_of(d, &variable);
                if (!variable.is_null()) x["variable"] = variable;
                params[d.name] = x;
            }
        passes.push_back({{"name", p.name}, {"type", p.type}, {"enabled", p.enabled}, {"params", params}});
    }
    json resources = json::array();
    for (const auto& r : g.resources) resources.push_back(r.name);
    json outputs = json::array();
    for (const auto& o : g.outputs) outputs.push_back(o.resource);
    return {{"path", g.path},         {"name", graph_display_name(g)}, {"description", g.description},
            {"variables", vars},      {"passes", passes},              {"resources", resources},
            {"outputs", outputs},     {"notes", g.notes}};
}

// ---- rendering ------------------------------------------------------------------------------

struct Readback {
    std::string name;
    const FormatInfo* format = nullptr;
    int width = 0, height = 0, channels = 0;
    bool downsample = false;        // render-size textures follow --ssaa down to the picture
    std::vector<uint8_t> bytes;     // 8-bit formats
    std::vector<float> floats;      // float and depth formats
};

// The names asked for, checked against the compiled graph before any GL work: resource names
// or pass.pin, with a did-you-mean. Empty: the graph's outputs.
std::vector<Readback> plan_readbacks(const CompiledGraph& cg, const GraphFile& g, std::vector<std::string> names,
                                     int ssaa) {
    if (names.empty())
        for (const auto& o : cg.outputs) names.push_back(o.resource);
    std::vector<std::string> known;
    for (const auto& r : cg.resources) known.push_back(r.name);
    std::vector<Readback> out;
    for (std::string name : names) {
        const size_t dot = name.find('.');
        if (cg.find_resource(name) < 0 && dot != std::string::npos)  // pass.pin -> the resource bound there
            for (const auto& p : g.passes)
                if (p.name == name.substr(0, dot) && p.outputs.count(name.substr(dot + 1)))
                    name = p.outputs.at(name.substr(dot + 1));
        const int r = cg.find_resource(name);
        if (r < 0) {
            std::string why;
            for (const auto& c : cg.culled) why += "; pass '" + c.name + "' is culled (" + c.reason + ")";
            std::string m = text::closest_match(name, known);
            throw std::invalid_argument("outputs: no resource '" + name + "' in the compiled graph" +
                                        (m.empty() ? "" : " (did you mean '" + m + "'?)") + "; its resources: " +
                                        [&] {
                                            std::string s;
                                            for (const auto& k : known) s += (s.empty() ? "" : ", ") + k;
                                            return s;
                                        }() + why);
        }
        const CompiledResource& res = cg.resources[size_t(r)];
        const FormatInfo* f = find_format(res.internal_format);
        if (res.kind != PinKind::Texture || !f)
            throw std::invalid_argument("outputs: '" + name + "' is a buffer, not an image");
        if (f->is_integer)
            throw std::invalid_argument("outputs: '" + name + "' has the integer format " + f->name +
                                        ", which has no image read-back");
        Readback rb;
        rb.name = name;
        rb.format = f;
        rb.channels = f->depth ? 1 : f->channels;
        rb.downsample = ssaa > 1 && res.width == cg.output_size.x && res.height == cg.output_size.y;
        out.push_back(rb);
    }
    return out;
}

py::array frames_array(Readback& rb, size_t frames, bool single) {
    std::vector<py::ssize_t> shape;
    if (!single) shape.push_back(py::ssize_t(frames));
    shape.push_back(rb.height);
    shape.push_back(rb.width);
    if (rb.channels > 1) shape.push_back(rb.channels);
    if (!rb.bytes.empty() || (rb.floats.empty() && !rb.format->is_float && !rb.format->depth))
        return to_numpy(std::move(rb.bytes), shape);
    return to_numpy(std::move(rb.floats), shape);
}

struct RenderArgs {
    std::string graph;
    std::vector<std::string> sets, outputs;
    std::string time, size = "1280x720", camera, timing = "auto";
    int ssaa = 1, warmup = 2;
    double orbit = 0;
};

py::tuple render_frames(const RenderArgs& a, const SceneRef& scene) {
    RenderOptions opt;
    opt.graph_path = a.graph;
    opt.sets = a.sets;
    opt.size = parse_size(a.size);
    opt.time = a.time.empty() ? default_time_range(*scene) : parse_time_range(a.time);
    if (a.time.empty()) std::fprintf(stderr, "note: %s\n", picked_time_note(opt.time, *scene, "the whole span").c_str());
    opt.timing = parse_timing_backend(a.timing);
    opt.camera_path = a.camera;
    opt.orbit_deg_per_s = a.orbit;
    opt.ssaa = a.ssaa;
    opt.warmup = a.warmup;
    opt.write_images = false;
    opt.quiet = true;
    check_render_limits(opt);  // the command's limits
    const bool single = a.time.find(':') == std::string::npos && !a.time.empty();
    std::vector<Readback> rbs;
    json timings;
    size_t frames = 0;
    std::string incomplete;  // the command's last line, when a pass dropped anything
    {
        py::gil_scoped_release nogil;
        timings = GlThread::get().call([&](Runtime& rt) {
            const GraphFile g = rt.load_graph(opt.graph_path, opt.sets);
            rbs = plan_readbacks(compile_graph(g, rt.registry, opt.size * std::max(1, opt.ssaa)), g, a.outputs, opt.ssaa);
            for (auto& rb : rbs) opt.keep.push_back(rb.name);  // out of the pool: still theirs after the frame
            RenderResult r = render(rt, *scene, opt, [&](const Executor& ex, size_t) {
                for (auto& rb : rbs) {
                    const Texture t = ex.texture(rb.name);
                    Image img = read_texture(t.id, t.width, t.height, 0, rb.channels);
                    if (rb.downsample) img = box_downsample(img, opt.ssaa);
                    rb.width = img.width;
                    rb.height = img.height;
                    if (rb.format->is_float || rb.format->depth)
                        rb.floats.insert(rb.floats.end(), img.pixels.begin(), img.pixels.end());
                    else
                        for (float v : img.pixels) rb.bytes.push_back(to_unorm8(v));
                }
                ++frames;
            });
            incomplete = incomplete_frames_line(r);
            return r.profiler.to_json({{"graph", opt.graph_path}, {"renderer", rt.gl->renderer()},
                                       {"size", {opt.size.x, opt.size.y}}, {"frames", r.frames},
                                       {"data", scene->source}, {"variables", r.compiled.variables},
                                       {"incomplete_frames", r.incomplete_frames}});
        });
    }
    if (!incomplete.empty()) std::fprintf(stderr, "%s\n", incomplete.c_str());
    py::dict arrays;
    for (auto& rb : rbs) arrays[py::str(rb.name)] = frames_array(rb, frames, single && frames == 1);
    return py::make_tuple(arrays, py::cast(opt.time.times()), from_json(timings));
}

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

py::dict run_quality(const std::string& graph, const std::vector<std::string>& sets, const SceneRef& scene,
                     const std::string& time, const std::string& size, int rays, int flicker_rays, bool own_line,
                     float max_distance, float depth_tolerance, const std::string& work_dir) {
    quality::QualityOptions q;
    q.flicker_rays = flicker_rays;
    q.own_line = own_line;
    q.graph_path = graph;
    q.sets = sets;
    q.size = parse_size(size);
    if (!time.empty()) q.time = parse_time_range(time);
    q.rays = rays;
    q.max_distance = max_distance;
    q.depth_tolerance = depth_tolerance;
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
    if (flicker_rays > 0) {
        d["reference_change"] = r.reference_flicker.reference_change;
        d["flicker_excess"] = r.reference_flicker.excess;
    }
    d["mae"] = r.error.mae;
    d["correlation"] = r.error.correlation;
    d["pixels"] = r.error.pixels;
    d["rays"] = rays;
    d["reach"] = r.reach;
    d["segments"] = r.segments;
    d["error"] = to_numpy(std::move(r.error.abs_error), {h, w});
    d["error_image"] = to_numpy(std::move(picture), {h, w, 4});
    d["ao"] = to_numpy(std::move(r.last.ao), {h, w});
    d["reference"] = to_numpy(std::move(r.reference), {h, w});
    d["line_id"] = to_numpy(std::move(r.last.line_id), {h, w});
    return d;
}

// quality(..., reference=...): fidelity against a reference graph (issue 42).
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
}  // namespace pathlet::python

PYBIND11_MODULE(_pathlet, m) {
    using namespace pathlet;
    using namespace pathlet::python;
    m.doc() = "C++ side of the pathlet module (use `import pathlet`)";
    py::register_exception_translator(&translate);

    py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene")
        .def_property_readonly("source", [](const Scene& s) { return s.source; })
        .def_property_readonly("line_count", [](const Scene& s) { return s.lines.line_count(); })
        .def_property_readonly("point_count", [](const Scene& s) { return s.lines.point_count(); })
        .def_property_readonly("time_range", [](const Scene& s) { return py::make_tuple(s.lines.time_min(), s.lines.time_max()); })
        .def_property_readonly("speed_range", [](const Scene& s) { return py::make_tuple(s.lines.speed_min(), s.lines.speed_max()); })
        .def_property_readonly("bounds", [](const Scene& s) {
            const Bounds b = s.bounds();
            return py::make_tuple(py::make_tuple(b.lo.x, b.lo.y, b.lo.z), py::make_tuple(b.hi.x, b.hi.y, b.hi.z));
        })
        .def_property_readonly("units", [](const Scene& s) {
            const Units& u = s.lines.units;
            return py::dict(py::arg("length") = u.length, py::arg("time") = u.time, py::arg("velocity") = u.velocity);
        })
        .def_property_readonly("timeless", [](const Scene& s) { return s.lines.timeless; })
        .def_property_readonly("wall_triangles", [](const Scene& s) { return s.mesh ? s.mesh->index.size() / 3 : 0; })
        .def("arrays", &scene_arrays);

    m.def("build_info", &build_description);
    m.def("phantom", [](const std::string& preset) {
        SceneSource src;
        src.phantom = preset;
        return std::const_pointer_cast<Scene>(load_scene_source(src));
    });
    m.def("load", [](const std::string& data, const std::string& mesh, const std::string& time_array,
                     const std::string& velocity_array, double time_step, const std::string& units, bool streamlines,
                     bool pseudo_time) {
        SceneSource src;
        src.data = data;
        src.mesh = mesh;
        src.load = {.time_array = time_array,
                    .velocity_array = velocity_array,
                    .time_step = time_step,
                    .streamlines = streamlines,
                    .pseudo_time = pseudo_time,
                    .units = units};
        return std::const_pointer_cast<Scene>(load_scene_source(src));
    });
    m.def("from_arrays", &scene_from_arrays);
    m.def("with_wall_file", [](const SceneRef& s, const std::string& path) {
        return std::const_pointer_cast<Scene>(with_wall(s, io::load_mesh(path)));
    });
    m.def("with_wall_arrays", [](const SceneRef& s, const Array<float>& v, const Array<int64_t>& t) {
        return std::const_pointer_cast<Scene>(with_wall(s, mesh_from_arrays(v, t)));
    });

    m.def("resolve_graph", &resolve_graph_path);
    // The user's --set texts with the hook paths they give made absolute and allowed (Runtime::user_sets).
    m.def("user_sets", [](const std::vector<std::string>& sets) {
        py::gil_scoped_release nogil;
        return GlThread::get().call([&](Runtime& rt) { return rt.user_sets(sets); });
    });
    m.def("describe_graph", [](const std::string& path, const std::vector<std::string>& sets) {
        json j;
        {
            py::gil_scoped_release nogil;
            j = GlThread::get().call([&](Runtime& rt) { return describe_graph(rt, path, sets); });
        }
        return from_json(j);
    });

    py::class_<RenderArgs>(m, "RenderArgs")
        .def(py::init<>())
        .def_readwrite("graph", &RenderArgs::graph)
        .def_readwrite("sets", &RenderArgs::sets)
        .def_readwrite("outputs", &RenderArgs::outputs)
        .def_readwrite("time", &RenderArgs::time)
        .def_readwrite("size", &RenderArgs::size)
        .def_readwrite("camera", &RenderArgs::camera)
        .def_readwrite("timing", &RenderArgs::timing)
        .def_readwrite("ssaa", &RenderArgs::ssaa)
        .def_readwrite("warmup", &RenderArgs::warmup)
        .def_readwrite("orbit", &RenderArgs::orbit);
    m.def("render", [](const RenderArgs& a, const std::shared_ptr<Scene>& s) { return render_frames(a, s); });

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
                        const std::string& time, const std::string& size, int rays, int flicker_rays, bool own_line,
                        float max_distance, float depth_tolerance, const std::string& work_dir) {
        return run_quality(graph, sets, s, time, size, rays, flicker_rays, own_line, max_distance, depth_tolerance,
                           work_dir);
    });
    m.def("quality_reference", &run_reference);
    m.def("transparency", [](const std::string& graph, const std::vector<std::string>& sets, const std::shared_ptr<Scene>& s,
                             const std::string& time, const std::string& size, int repeat, double focus_share,
                             double visible) {
        return run_transparency(graph, sets, s, time, size, repeat, focus_share, visible);
    });
    // The files and tables `pathlet bench` writes, from a report (results.json's content).
    m.def("summary_csv", [](const std::string& report) { return cli::bench::summary_csv(json::parse(report)); });
    m.def("frames_csv", [](const std::string& report) { return cli::bench::frames_csv(json::parse(report)); });
    m.def("write_report_dir", [](const std::string& dir, const std::string& report) {
        return cli::bench::write_report_dir(dir, json::parse(report));
    });
    m.def("gl_renderer", [] {
        py::gil_scoped_release nogil;
        return GlThread::get().call([](Runtime& rt) { return rt.ensure_gl(true).renderer(); });
    });
    m.def("close", [] {
        py::gil_scoped_release nogil;
        GlThread::get().close();
    });
    m.def("closed", [] { return GlThread::get().closed(); });
}
