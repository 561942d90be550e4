"""Pathlet from Python: load pathlines, open render graphs, render frames to NumPy arrays,
benchmark per pass and measure LineAO quality, through the same code as the ``pathlet``
command (which stays the reference for every behaviour).

    import pathlet
    scene = pathlet.phantom("small")
    g = pathlet.Graph("variant1_lineao").set(samples=32, window=0.6)
    frame = pathlet.render(g, scene, time=2.0, size=(640, 360), outputs=["final", "ao"])
    frame["final"]      # (360, 640, 4) uint8, the picture `pathlet render` writes
    frame["ao"]         # (360, 640) float32, LineAO's AO map
    pathlet.bench(["variant1_lineao", "isl"], scene, sizes=["640x360"]).passes()   # DataFrame

One GL context per process, owned by one thread that runs every render in turn; the GIL is
released while it works, so other Python threads go on. pathlet.close() ends it (also at exit);
later calls raise ClosedError.
"""

import atexit
import csv
import io
import json
import os
import tempfile
import warnings

from ._errors import ClosedError, DataError, GlError, GraphError, PassError

try:
    from . import _pathlet as _c
except ImportError as _e:  # the pure-Python parts (pathlet.plot) still work
    _c = None
    _import_error = _e

__all__ = [
    "Scene", "Graph", "Rendered", "Results", "phantom", "load", "from_arrays", "render", "bench",
    "run_experiment", "quality", "quality_options", "close", "closed", "gl_renderer", "build_info", "GraphError", "DataError",
    "PassError", "GlError", "ClosedError",
]


def _core():
    if _c is None:
        raise ImportError(f"pathlet's compiled module is not available: {_import_error}")
    return _c


# ---- values as the command line writes them ---------------------------------------------------

def _value_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return v
    if hasattr(v, "tolist"):
        v = v.tolist()
    if isinstance(v, (list, tuple)):
        return json.dumps([float(x) for x in v])
    if isinstance(v, float):
        return repr(v)
    return str(v)


def _size_text(size):
    if isinstance(size, str):
        return size
    w, h = size
    return f"{int(w)}x{int(h)}"


def _time_text(time):
    if time is None:
        return ""
    if isinstance(time, str):
        return time
    if isinstance(time, (tuple, list)):
        if len(time) not in (2, 3):
            raise ValueError(f"time: expected T, (START, END) or (START, END, STEP), got {time!r}")
        return ":".join(repr(float(x)) for x in time)
    return repr(float(time))


# ---- data -------------------------------------------------------------------------------------

class Scene:
    """Pathlines (and an optional wall mesh) ready to render. Make one with phantom(), load()
    or from_arrays()."""

    def __init__(self, handle):
        self._h = handle

    source = property(lambda self: self._h.source)
    line_count = property(lambda self: self._h.line_count)
    point_count = property(lambda self: self._h.point_count)
    time_range = property(lambda self: self._h.time_range, doc="(first, last) time in seconds")
    speed_range = property(lambda self: self._h.speed_range)
    bounds = property(lambda self: self._h.bounds, doc="((x, y, z) low, (x, y, z) high)")
    wall_triangles = property(lambda self: self._h.wall_triangles)
    units = property(lambda self: self._h.units, doc="{length, time, velocity}; '' where unknown")
    timeless = property(lambda self: self._h.timeless, doc="lines without time (streamlines): drawn whole")
    bundles = property(lambda self: list(self._h.bundles),
                       doc="bundle names in bundle order: the data files' stems (colormap=bundle colours by them)")

    def arrays(self):
        """Copies of the data: points (n, 3), offsets (lines + 1), times (n), velocity (n, 3)."""
        return self._h.arrays()

    def with_wall(self, path=None, *, vertices=None, triangles=None):
        """This scene with a wall mesh from a file (glTF, STL, OBJ) or from arrays."""
        if path is not None:
            return Scene(_core().with_wall_file(self._h, os.fspath(path)))
        if vertices is None or triangles is None:
            raise ValueError("with_wall: give a mesh file, or vertices (n, 3) and triangles (m, 3)")
        return Scene(_core().with_wall_arrays(self._h, vertices, triangles))

    def __repr__(self):
        t0, t1 = self.time_range
        wall = f", wall {self.wall_triangles} triangles" if self.wall_triangles else ""
        return (f"<pathlet.Scene {self.source!r}: {self.line_count} lines, {self.point_count} points, "
                f"t {t0:.2f}..{t1:.2f} s{wall}>")


def phantom(preset="study"):
    """The built-in aortic-arch phantom ("study": ~3169 lines like the study's data; "small":
    a few hundred, for quick looks), generated once and cached as the command line does.
    "study:density=16": 16 times the lines (more seeds, the same vessel and time span)."""
    return Scene(_core().phantom(preset))


def load(data, mesh=None, *, time_array="", velocity_array="", time_step=0.0, units="", streamlines=False,
         pseudo_time=False):
    """Pathlines from a file (.vtk, .vtp, .pathlet, .trk, .tck, text rows) and an optional wall
    mesh, as ``pathlet render --data DATA --mesh MESH`` loads them. data may be a list of files,
    folders (their data files) or globs, joined as ``--data A B ...`` joins them: each file a
    bundle named after it (Scene.bundles; colormap=bundle colours by it). units: "LENGTH[,VELOCITY]"
    where the file does not say them (as --units; the speed legend shows them, else "speed");
    streamlines / pseudo_time as the options of those names. Bad files raise DataError."""
    return Scene(_core().load(_data_list(data), os.fspath(mesh) if mesh else "", time_array, velocity_array,
                              float(time_step), units, bool(streamlines), bool(pseudo_time)))


def _data_list(data):
    return [os.fspath(d) for d in data] if isinstance(data, (list, tuple)) else [os.fspath(data)]


def default_graph(data):
    """The shipped graph ``pathlet render --data DATA`` draws without a graph: "tracts_lineao"
    for tractography (direction colours), else "variant1_lineao"."""
    return _core().default_graph(_data_list(data))


def from_arrays(points, offsets, times, velocity=None, *, wall=None, source="arrays", units=""):
    """Pathlines from NumPy arrays: points (n, 3), offsets (lines + 1: where each line starts,
    then n), times (n) and optionally velocity (n, 3; else from differences, as the importers
    do). They go through the importers' repair step (its warnings become Python warnings).
    wall: a mesh file or (vertices, triangles). units: "LENGTH[,VELOCITY]", e.g. "mm" or
    "m,m/s" (as --units); without them the speed legend says "speed" with no unit."""
    import numpy as np

    h, notes = _core().from_arrays(np.asarray(points, np.float32), np.asarray(offsets, np.int64),
                                   np.asarray(times, np.float32),
                                   None if velocity is None else np.asarray(velocity, np.float32), source, units)
    for n in notes:
        warnings.warn(f"{source}: {n}", stacklevel=2)
    scene = Scene(h)
    if wall is None:
        return scene
    if isinstance(wall, (str, os.PathLike)):
        return scene.with_wall(wall)
    vertices, triangles = wall
    return scene.with_wall(vertices=vertices, triangles=triangles)


# ---- graphs -----------------------------------------------------------------------------------

class Graph:
    """A graph file (or a shipped graph's name) with overrides, checked as ``--set`` checks
    them: set("window", 0.6), set(samples=32), set("lineao.strength=2"), g["radius"] = 3.
    A wrong name or value raises GraphError with the JSON pointer and a did-you-mean, and
    leaves the graph as it was. A hook is a file on the shader path or next to the graph, or
    a path of yours (relative to the current folder): set("fill_list.color_hook=my_fade.glsl").
    What resolving it did that you may not expect (a replaced hook's parameters dropped) is
    a warning and in notes."""

    def __init__(self, graph="variant1_lineao", sets=(), *, label=None):
        self.path = _core().resolve_graph(os.fspath(graph))
        self._sets = []
        self._info = _core().describe_graph(self.path, [])
        self.label = label
        self._warn_notes(())
        for s in sets:
            self.set(s)

    name = property(lambda self: self._info["name"])
    description = property(lambda self: self._info["description"])
    sets = property(lambda self: tuple(self._sets), doc="the overrides, as --set NAME=VALUE texts "
                                                        "(hook paths made absolute)")
    notes = property(lambda self: list(self._info["notes"]), doc="what resolving the graph did that you may "
                                                                 "not expect (a replaced hook's parameters dropped)")

    def _warn_notes(self, before):
        for n in self._info["notes"]:
            if n not in before:
                warnings.warn(f"pathlet: {n}", stacklevel=3)

    def set(self, *assignments, **values):
        new = list(assignments) + [f"{k}={_value_text(v)}" for k, v in values.items()]
        for a in new:
            if not isinstance(a, str):
                raise TypeError(f"set: expected 'NAME=VALUE' or NAME=VALUE keywords, got {a!r}")
        new = _core().user_sets(new)  # a hook path of yours: absolute, as the command line makes it
        before = self._info["notes"]
        self._info = _core().describe_graph(self.path, self._sets + new)
        self._sets += new
        self._warn_notes(before)
        return self

    def __setitem__(self, name, value):
        self.set(f"{name}={_value_text(value)}")

    def __getitem__(self, name):
        """A variable's value, or a pass parameter's as pass.param."""
        if name in self._info["variables"]:
            return self._info["variables"][name]["value"]
        if "." in name:
            p, param = name.split(".", 1)
            for x in self._info["passes"]:
                if x["name"] == p and param in x["params"]:
                    return x["params"][param]["value"]
        raise KeyError(f"{self.name}: no variable or pass parameter '{name}'")

    def variables(self):
        """{name: {value, type, default, min, max, choices, doc}}."""
        return {k: dict(v) for k, v in self._info["variables"].items()}

    def passes(self):
        """[{name, type, enabled, params: {name: {value, variable, type, default, doc, ...}}}]."""
        return [dict(p) for p in self._info["passes"]]

    def params(self, pass_name):
        for p in self._info["passes"]:
            if p["name"] == pass_name:
                return dict(p["params"])
        raise KeyError(f"{self.name}: no pass '{pass_name}'; its passes: "
                       + ", ".join(p["name"] for p in self._info["passes"]))

    def resources(self):
        return list(self._info["resources"])

    def copy(self, **values):
        g = Graph(self.path, self._sets, label=self.label)
        return g.set(**values) if values else g

    def __repr__(self):
        sets = "".join(f" --set {s}" for s in self._sets)
        return f"<pathlet.Graph {self.name}{sets}>"


def _graph(graph):
    return graph if isinstance(graph, Graph) else Graph(graph)


# ---- rendering --------------------------------------------------------------------------------

class Rendered(dict):
    """Images by resource name (uint8 for 8-bit formats, float32 for float and depth), with a
    leading frame axis for a time range. rgba: the graph's first output. times: the frame
    times. timings: the profiler's report (as --report writes it)."""

    def __init__(self, arrays, times, timings, first):
        super().__init__(arrays)
        self.times = list(times)
        self.timings = timings
        self._first = first

    @property
    def rgba(self):
        return self[self._first]

    def passes(self):
        """Per pass: median, p5, p95 ms (backend-measured), as a DataFrame or a list of dicts."""
        rows = [{"pass": p["name"], "depth": p["depth"], "median_ms": p["gpu_ms"]["median"],
                 "p5_ms": p["gpu_ms"]["p5"], "p95_ms": p["gpu_ms"]["p95"], "share_pct": p["share_pct"]}
                for p in self.timings["passes"]]
        return _table(rows)


def _camera_file(camera, stack):
    if camera is None:
        return ""
    if isinstance(camera, (str, os.PathLike)):
        return os.fspath(camera)
    keys = camera if "keyframes" in camera else {"keyframes": [dict({"time": 0}, **camera)]}
    f = tempfile.NamedTemporaryFile("w", suffix=".json", prefix="pathlet_camera_", delete=False)
    with f:
        json.dump(keys, f)
    stack.append(f.name)
    return f.name


def render(graph, scene, time=None, size=(1280, 720), *, outputs=None, camera=None, orbit=0.0, ssaa=1,
           warmup=2, timing="auto"):
    """Renders like ``pathlet render`` (same defaults, warm-up included) but returns the images
    instead of writing them. time: T, (START, END[, STEP]) or "A:B:STEP"; None: the data's
    whole span in 0.25 s steps (said on stderr). outputs: resource names or pass.pin (e.g. ["final", "ao"]);
    default the graph's outputs. camera: a camera path file, or {"eye", "target", "up", "fov"}."""
    g = _graph(graph)
    a = _core().RenderArgs()
    a.graph = g.path
    a.sets = list(g.sets)
    a.outputs = list(outputs or [])
    a.time = _time_text(time)
    a.size = _size_text(size)
    a.orbit = float(orbit)
    a.ssaa = int(ssaa)
    a.warmup = int(warmup)
    a.timing = timing
    temps = []
    try:
        a.camera = _camera_file(camera, temps)
        arrays, times, timings = _core().render(a, scene._h)
    finally:
        for t in temps:
            os.unlink(t)
    first = a.outputs[0] if a.outputs else g._info["outputs"][0]
    if first not in arrays:  # pass.pin asked for: its resource's name is the key
        first = next(iter(arrays))
    return Rendered(arrays, times, timings, first)


# ---- benchmarks and experiments ---------------------------------------------------------------

def _table(rows):
    try:
        import pandas as pd
    except ImportError:
        return rows
    return pd.DataFrame(rows)


def _csv_rows(text):
    rows = []
    for r in csv.DictReader(io.StringIO(text)):
        for k, v in r.items():
            if k in ("depth", "n", "frame", "warmup"):
                r[k] = int(v)
            elif k.endswith("_ms") or k.endswith("_pct"):
                r[k] = float(v)
        rows.append(r)
    return rows


class Results:
    """What ``pathlet bench`` records: report is results.json's content (every run, every
    frame, machine, GL renderer). passes() is summary.csv, frames() frames.csv."""

    def __init__(self, report):
        self.report = report

    @classmethod
    def load(cls, path):
        with open(path) as f:
            return cls(json.load(f))

    runs = property(lambda self: self.report["runs"])

    def passes(self):
        """Per run and pass (and the whole frame as "(frame)"): median, p5, p95 ms and share."""
        return _table(_csv_rows(_core().summary_csv(json.dumps(self.report))))

    def frames(self):
        """Every frame of every run: gpu_ms per pass and for the frame."""
        return _table(_csv_rows(_core().frames_csv(json.dumps(self.report))))

    def save(self, folder):
        """Writes results.json, summary.csv, frames.csv and the SVG plots, as bench does."""
        return _core().write_report_dir(os.fspath(folder), json.dumps(self.report))

    def plot(self, folder, formats=("png", "pdf"), baseline=None):
        """The Matplotlib figures (pathlet.plot) into folder; returns the files."""
        from . import plot
        return plot.write_all(self.report, os.fspath(folder), formats=formats,
                              baseline=baseline.report if isinstance(baseline, Results) else baseline)

    def __repr__(self):
        r = self.report
        return f"<pathlet.Results {r.get('experiment')}: {len(r['runs'])} of {r.get('planned_runs')} runs>"


def bench(graphs, scene=None, *, sizes=("1280x720",), time=None, frames=10, warmup=3, sets=(), sweep=None,
          timing="auto", out=None):
    """Times graphs as ``pathlet bench GRAPHS`` does (same runs, same numbers): graphs are names,
    files or Graph objects (with their overrides); sweep=(NAME, [values]) runs each graph at
    every value. scene: default the study phantom. time: None measures the middle of the
    data's time span (said on stderr; the report's data entries hold it). out: also write the
    results folder."""
    if isinstance(graphs, (str, Graph)):
        graphs = [graphs]
    entries, labels = [], set()
    for i, g in enumerate(graphs):
        g = _graph(g)
        label = g.label or g.name
        if label in labels:
            label += f" #{i + 1}"
        labels.add(label)
        entries.append({"graph": g.path, "label": label, "set": list(g.sets)})
    exp = {"name": "bench", "graphs": entries, "sizes": [_size_text(s) for s in sizes],
           "frames": int(frames), "warmup": int(warmup),
           "set": _core().user_sets([s if isinstance(s, str) else f"{s[0]}={_value_text(s[1])}" for s in sets])}
    if time is not None:
        exp["time"] = _time_text(time)
    if sweep is not None:
        name, values = sweep
        exp["sweep"] = {"param": name, "values": [_value_text(v) for v in values]}
    a = _core().BenchArgs()
    a.experiment_json = json.dumps(exp)
    a.timing = timing
    a.out = os.fspath(out) if out else ""
    return Results(_core().bench(a, scene._h if scene is not None else None))


def run_experiment(path, scene=None, *, out=None, sizes=None, time=None, frames=None, warmup=None, sets=(),
                   shard=None, images=None, timing="auto"):
    """Runs an experiment file as ``pathlet bench --experiment PATH`` does; the keywords
    override it as the options of the same names do. scene replaces its data sets (as --data).
    out: write the results folder (and, unless images=False, one image per run)."""
    a = _core().BenchArgs()
    a.experiment = os.fspath(path)
    a.sizes = [_size_text(s) for s in sizes] if sizes else []
    a.time = _time_text(time)
    a.frames = -1 if frames is None else int(frames)
    a.warmup = -1 if warmup is None else int(warmup)
    a.sets = _core().user_sets(list(sets))
    a.shard = shard or ""
    a.timing = timing
    a.out = os.fspath(out) if out else ""
    a.images = bool(out) and images is not False
    return Results(_core().bench(a, scene._h if scene is not None else None))


# ---- quality ----------------------------------------------------------------------------------

def quality(graph, scene, time=None, size=(320, 180), *, transparency=False,
            focus_share=0.1, visible=0.05, repeat=1, reference=None, out=None, ppd=None, **ao_options):
    """``pathlet quality`` as numbers (time None: 11 frames 0.04 s apart from the middle of the
    data's span, said on stderr; the study phantom's 9:9.4:0.04): flicker (mean |dAO| where the same line stays),
    geometry_change, with flicker_rays > 0 reference_change and flicker_excess (how much the
    ray-traced AO changes at those pixels, and the AO's change beyond it), mae and correlation
    against a ray-traced AO of the last frame, and the images error (|error| per pixel),
    error_image (RGBA, as the command writes it), ao, reference and line_id. A graph without
    AO gives {"graph", "not_measured": why}. The ray-traced AO's options are the command's,
    with '_' for '-' (rays=256, flicker_rays=256, max_distance=10, include_own_line=False,
    gbuffer_point=False, depth_tolerance=0.002): pathlet.quality_options() lists them with their
    defaults and what each does.

    transparency=True: ``pathlet quality --transparency`` instead, for an OIT graph:
    focus_visibility, focus_unoccluded, focus_ink_share, context_coverage, alpha_change_mean,
    alpha_change_p95, alpha_change_max, max_alpha_change_per_frame, overflow, pixel_coverage
    (focus: the fastest focus_share of the data's segments; a context segment counts as seen
    with ink per footprint >= visible; repeat frames per time, > 1 for a frozen view).

    reference=GRAPH: ``pathlet quality GRAPH --reference REF`` instead: both rendered
    over the same times, size and camera (graph's sets for both, the reference's own sets after
    them), compared over the pixels either covers: ssim (windowed, Wang et al. 2004, 11x11
    Gaussian on luminance), psnr, rmse, share_over (fraction more than 8/255 apart), flip (mean
    LDR-FLIP, Andersson et al. 2020, at ppd pixels per degree, default 67 as the command's --ppd;
    flip_all over every pixel), pixels,
    flicker_excess (frame-to-frame change beyond the reference's own; flicker and
    reference_change are the two changes), per_frame (the measures per frame); out=DIR writes
    the difference and FLIP images there (their paths in images)."""
    g = _graph(graph)
    if reference is None and ppd is not None:
        raise ValueError("ppd needs reference= (FLIP compares two graphs' pictures)")
    if reference is not None:
        r = _graph(reference)
        return _core().quality_reference(g.path, list(g.sets), r.path, list(r.sets), scene._h, _time_text(time),
                                         _size_text(size), "" if out is None else str(out),
                                         None if ppd is None else float(ppd))
    if transparency:
        return _core().transparency(g.path, list(g.sets), scene._h, _time_text(time), _size_text(size), int(repeat),
                                    float(focus_share), float(visible))
    with tempfile.TemporaryDirectory(prefix="pathlet_quality_") as work:
        return _core().quality(g.path, list(g.sets), scene._h, _time_text(time), _size_text(size), ao_options, work)


def quality_options():
    """The ray-traced AO measure's options of quality(): a list of {"name", "default", "doc"}
    (the command's --NAME with '-' for '_')."""
    return _core().quality_options()


# ---- the context --------------------------------------------------------------------------------

def build_info():
    """What this build has and where it runs from (as ``pathlet --version``): lean or full,
    a bundle or a build tree, the share folder."""
    return _core().build_info()


def gl_renderer():
    """The GL renderer string (creates the process's context if there is none yet)."""
    return _core().gl_renderer()


def close():
    """Frees the GL context and plugins; later renders raise ClosedError."""
    if _c is not None:
        _c.close()


def closed():
    return _c is not None and _c.closed()


atexit.register(close)
