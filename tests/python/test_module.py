# import pathlet: the module gives what the command gives (same pictures, same errors, same
# numbers), NumPy in and out, and its context rules (one GL thread, GIL released, closed is closed).
import json
import os
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from conftest import read_png

SMALL = ["--phantom", "small", "--quiet"]


def test_render_equals_the_command_byte_for_byte(pathlet, cli, scene, tmp_path):
    cli("render", "variant1_lineao", "--time", "2", "--size", "160x90", "--out", str(tmp_path), *SMALL)
    expected = read_png(tmp_path / "variant1_lineao" / "00000.png")
    got = pathlet.render("variant1_lineao", scene, time=2, size=(160, 90))
    assert got.rgba.dtype == np.uint8 and got.rgba.shape == (90, 160, 4)
    assert np.array_equal(got.rgba, expected)
    # An override goes through as --set does: the same picture as the command's, another than before.
    cli("render", "variant1_lineao", "--time", "2", "--size", "160x90", "--set", "window=0.3",
        "--out", str(tmp_path / "set"), *SMALL)
    g = pathlet.Graph("variant1_lineao").set(window=0.3)
    short = pathlet.render(g, scene, time=2, size="160x90").rgba
    assert np.array_equal(short, read_png(tmp_path / "set" / "variant1_lineao" / "00000.png"))
    assert not np.array_equal(short, got.rgba)


def test_intermediates_come_back_by_resource_or_pass_pin(pathlet, scene):
    r = pathlet.render("variant1_lineao", scene, time=2, size=(160, 90), outputs=["final", "ao", "normal_depth"])
    ao, nd = r["ao"], r["normal_depth"]
    assert ao.dtype == np.float32 and ao.shape == (90, 160)
    assert nd.shape == (90, 160, 4)
    covered = np.linalg.norm(nd[..., :3], axis=-1) > 0.5
    assert covered.sum() > 200
    assert np.all(np.isfinite(ao)) and ao.min() >= 0 and ao.max() <= 1.0001
    assert ao[covered].mean() < 0.97, "LineAO darkens the covered pixels"
    assert ao[~covered].min() > 0.999, "and leaves the background open"
    same = pathlet.render("variant1_lineao", scene, time=2, size=(160, 90), outputs=["lineao.ao"])
    assert np.array_equal(same["ao"], ao)
    with pytest.raises(ValueError, match=r"no resource 'aoo'.*did you mean 'ao'"):
        pathlet.render("variant1_lineao", scene, time=2, size=(160, 90), outputs=["aoo"])


def test_a_time_range_gives_a_frame_axis(pathlet, scene):
    r = pathlet.render("isl", scene, time=(2, 2.08, 0.04), size=(64, 36))
    assert r.rgba.shape == (3, 36, 64, 4)
    assert r.times == pytest.approx([2.0, 2.04, 2.08])
    assert not np.array_equal(r.rgba[0], r.rgba[2]), "the pathlets move"
    single = pathlet.render("isl", scene, time=2.08, size=(64, 36))
    assert np.array_equal(single.rgba, r.rgba[2])
    table = r.passes()
    assert list(table["pass"])[0] == "isl" and (table["median_ms"] > 0).all()


def test_set_errors_carry_the_pointer_and_did_you_mean_like_set(pathlet, cli, scene):
    g = pathlet.Graph("variant1_lineao").set(samples=8)
    with pytest.raises(pathlet.GraphError) as e:
        g.set(sampels=3)
    assert e.value.pointer == "/variables"
    assert "did you mean 'samples'" in str(e.value)
    r = cli("render", "variant1_lineao", "--set", "sampels=3", "--size", "8x8", "--time", "1", *SMALL, check=False)
    tail = str(e.value).split("variant1_lineao.json", 1)[1]  # the folder is spelt differently
    assert r.returncode == 1 and tail in r.stderr, "the command's message, word for word"
    with pytest.raises(pathlet.GraphError) as e:
        g["lineao.raduis"] = 3
    assert e.value.pointer == "/passes/2/params" and "did you mean 'radii'" in str(e.value)
    with pytest.raises(pathlet.GraphError) as e:
        g.set(samples=1000)
    assert e.value.pointer.startswith("/variables/samples") and "1000" in str(e.value)
    assert g.sets == ("samples=8",) and g["samples"] == 8 and g["lineao.samples"] == 8, "a failed set changes nothing"
    assert g.variables()["samples"]["max"] == 128
    assert g.params("lineao")["samples"]["variable"] == "samples"
    with pytest.raises(pathlet.GraphError, match="no_such_graph"):
        pathlet.Graph("no_such_graph")


def helix_arrays(n_lines=6, n=200):
    t = np.linspace(0, 4, n, dtype=np.float32)
    pts, offsets = [], [0]
    for k in range(n_lines):
        a = t * 2 + k
        pts.append(np.stack([np.cos(a) * 10, np.sin(a) * 10, t * 5 + k], axis=1))
        offsets.append(offsets[-1] + n)
    return np.concatenate(pts).astype(np.float32), np.array(offsets), np.tile(t, n_lines)


def test_arrays_in_go_through_the_importers_repairs(pathlet):
    pts, off, times = helix_arrays()
    with pytest.warns(UserWarning, match="derived velocity"):
        s = pathlet.from_arrays(pts, off, times)
    assert (s.line_count, s.point_count) == (6, 1200)
    back = s.arrays()
    assert np.allclose(back["points"], pts) and np.array_equal(back["offsets"], off)
    assert np.linalg.norm(back["velocity"], axis=1).min() > 0, "velocity from differences"
    img = pathlet.render("isl", s, time=3, size=(96, 64), outputs=["final"]).rgba
    assert (img[..., :3].astype(int).sum(-1) != img[0, 0, :3].astype(int).sum()).sum() > 100, "the lines are drawn"
    pts_ok = pts.copy()
    pts[5] = np.nan
    with pytest.warns(UserWarning, match="NaN|non-finite"):
        assert pathlet.from_arrays(pts, off, times, velocity=back["velocity"]).point_count == 1199
    with pytest.raises(ValueError, match="offsets"):
        pathlet.from_arrays(pts, off[:-1], times)
    with pytest.raises(ValueError, match=r"times: expected shape \(1200\)"):
        pathlet.from_arrays(pts, off, times[:10])
    assert s.units["length"] == "" and s.units["velocity"] == "", "unknown unless given"
    with pytest.warns(UserWarning):
        mm = pathlet.from_arrays(pts_ok, off, times, units="mm,mm/s")
    assert mm.units["length"] == "mm" and mm.units["velocity"] == "mm/s", "as --units gives them"
    with pytest.raises(ValueError, match="at most two units"):
        pathlet.from_arrays(pts_ok, off, times, units="mm,mm/s,x")
    walled = s.with_wall(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0]], triangles=[[0, 1, 2]])
    assert walled.wall_triangles == 1 and s.wall_triangles == 0
    with pytest.raises(ValueError, match="not one of the 3 vertices"):
        s.with_wall(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0]], triangles=[[0, 1, 3]])


def test_files_load_as_the_command_loads_them(pathlet, root, tmp_path):
    s = pathlet.load(os.path.join(root, "tests/io/fixtures/vtk42_ascii_mixed.vtk"))
    assert s.line_count > 0 and s.source.endswith("vtk42_ascii_mixed.vtk")
    bad = tmp_path / "bad.vtk"
    bad.write_text("# vtk DataFile Version 4.2\nbroken\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n1 2\n")
    with pytest.raises(pathlet.DataError, match="bad.vtk"):
        pathlet.load(bad)


def test_bench_gives_the_commands_report(pathlet, cli, scene, tmp_path):
    res = pathlet.bench(["variant1_lineao", "isl", "isl"], scene, sizes=["64x36", "96x54"], time=2, frames=3,
                        warmup=1)
    assert [r["meta"]["label"] for r in res.runs] == ["variant1_lineao", "variant1_lineao", "isl", "isl",
                                                      "isl #3", "isl #3"]
    rows = res.passes()
    frame = rows[rows["pass"] == "(frame)"]
    assert len(frame) == 6 and (frame["n"] == 3).all()
    assert list(frame["median_ms"]) == pytest.approx([r["frame"]["gpu_ms"]["median"] for r in res.runs], abs=1e-4)
    assert set(rows[rows["label"] == "isl"]["pass"]) >= {"isl", "wall", "edge_aa", "overlay"}
    assert len(res.frames()) > 0
    # The command's report of the same runs has the same shape: labels, passes, columns.
    cli("bench", "variant1_lineao,isl,isl", "--size", "64x36,96x54", "--time", "2", "--frames", "3",
        "--warmup", "1", "--report", str(tmp_path / "cmd"), *SMALL)
    cmd = json.loads((tmp_path / "cmd.json").read_text())
    assert [(r["meta"]["label"], r["meta"]["size"], [p["name"] for p in r["passes"]]) for r in cmd["runs"]] == \
           [(r["meta"]["label"], r["meta"]["size"], [p["name"] for p in r["passes"]]) for r in res.runs]
    sweep = pathlet.bench([pathlet.Graph("isl", label="ISL")], scene, sizes=["64x36"], time=2, frames=2, warmup=0,
                          sweep=("window", [0.5, 1]))
    assert [r["meta"]["label"] for r in sweep.runs] == ["ISL window=0.5", "ISL window=1"]
    with pytest.raises(pathlet.GraphError, match="no_such"):
        pathlet.bench(["isl"], scene, sizes=["32x24"], frames=1, warmup=0, sets=["no_such=1"])


def test_experiment_files_run_as_with_the_command(pathlet, root, scene, tmp_path):
    exp = tmp_path / "e.json"
    exp.write_text(json.dumps({"graphs": ["isl", {"graph": "variant1_lineao", "label": "V1"}],
                               "data": [{"phantom": "small"}], "sizes": ["64x36"], "time": 2, "frames": 2,
                               "warmup": 0}))
    res = pathlet.run_experiment(exp, out=tmp_path / "out", shard="1/2")
    assert [r["meta"]["index"] for r in res.runs] == [1] and res.report["shard"] == {"index": 1, "count": 2}
    for f in ("results.json", "summary.csv", "frames.csv", "passes.svg"):
        assert (tmp_path / "out" / f).is_file(), f
    assert (tmp_path / "out" / res.runs[0]["meta"]["image"]).is_file()
    exp.write_text(json.dumps({"graphs": ["isl"], "sizez": ["64x36"]}))
    with pytest.raises(pathlet.DataError, match=r"e.json: /sizez: unknown key 'sizez' \(did you mean 'sizes'\?\)"):
        pathlet.run_experiment(exp)


def test_quality_numbers_and_image_are_the_commands(pathlet, cli, scene, tmp_path):
    args = ["--time", "2:2.08:0.04", "--size", "96x54", "--rays", "16", "--flicker-rays", "8"]
    out = cli("quality", "variant1_lineao", *args, "--out", str(tmp_path), "--phantom", "small").stdout
    q = pathlet.quality("variant1_lineao", scene, time="2:2.08:0.04", size=(96, 54), rays=16, flicker_rays=8)
    assert f"changes by {q['reference_change']:.5f} at those pixels" in out
    assert f"|dAO - dRT|: {q['flicker_excess']:.5f}" in out
    assert f"mean |dAO| {q['flicker']:.5f} over {q['stable_pixels']} stable pixels" in out
    assert f"MAE {q['mae']:.4f}, correlation {q['correlation']:.3f} over {q['pixels']} px" in out
    assert np.array_equal(q["error_image"], read_png(tmp_path / "variant1_lineao_error.png"))
    assert q["error"].shape == (54, 96) and q["reference"].shape == (54, 96)
    covered = q["line_id"] >= 0
    assert np.allclose(q["error"][covered], np.abs(q["ao"] - q["reference"])[covered], atol=1e-6)
    assert pathlet.quality("isl", scene, time="2:2.08:0.04", size=(32, 18), rays=4)["not_measured"].startswith("no AO")
    with pytest.raises(ValueError, match="two frames"):
        pathlet.quality("variant1_lineao", scene, time=2, size=(32, 18))
    with pytest.raises(ValueError, match=r"rays must be >= 1 \(got 0\)"):
        pathlet.quality("variant1_lineao", scene, time="2:2.08:0.04", size=(32, 18), rays=0)


def _readme_fade(root):
    """The README's "Writing a fade strategy" GLSL block, as printed."""
    text = open(os.path.join(root, "README.md")).read()
    start = text.index("```glsl\n", text.index("Writing a fade strategy")) + len("```glsl\n")
    return text[start:text.index("\n```", start)] + "\n"


def _isl_stats(results):
    return next(p for p in results.runs[0]["passes"] if p["name"] == "isl")["stats"]


def test_without_a_time_bench_and_quality_measure_inside_the_data(pathlet, scene):
    res = pathlet.bench(["isl"], scene, sizes=["64x36"], frames=1, warmup=0)
    assert res.report["data"][0]["time"] == "2", "the middle of the small phantom's 0..4 s"
    assert _isl_stats(res)["segments"] > 100 and _isl_stats(res)["lines"] > 10, "frames with lines in them"
    # What the old default (t = 9 s) measured: an empty picture.
    late = pathlet.bench(["isl"], scene, sizes=["64x36"], frames=1, warmup=0, time=9)
    assert _isl_stats(late)["segments"] == 0
    q = pathlet.quality("variant1_lineao", scene, size=(32, 18), rays=2, flicker_rays=0)
    assert q["frames"] == 11 and q["times"] == pytest.approx((2.0, 2.4))


def test_a_hook_path_of_yours_and_its_parameters(pathlet, scene, root, tmp_path, monkeypatch):
    (tmp_path / "my_fade.glsl").write_text(_readme_fade(root))
    monkeypatch.chdir(tmp_path)  # a path relative to the current folder, as on the command line
    g = pathlet.Graph("variant2_oit")
    assert g["fill_list.tail_fade"] == 0.5
    with pytest.warns(UserWarning, match=r"color_hook 'my_fade.glsl' replaces 'fade_opacity.frag'.*dropped: "
                                         r"head_fade, tail_fade"):
        g.set("fill_list.color_hook=my_fade.glsl")
    assert g["fill_list.color_hook"] == str(tmp_path / "my_fade.glsl")
    assert g["fill_list.keep_slow"] == 0.15, "the new hook's parameters"
    with pytest.raises(KeyError):
        g["fill_list.tail_fade"]
    with pytest.raises(pathlet.GraphError, match="did you mean 'keep_slow'"):
        g.set("fill_list.keep_slwo=0.2")
    faded = pathlet.render(g, scene, time=2, size=(96, 54)).rgba
    plain = pathlet.render("variant2_oit", scene, time=2, size=(96, 54)).rgba
    ink = lambda img: float((255 - img[..., 1].astype(np.float64)).sum())  # noqa: E731
    assert not np.array_equal(faded, plain)
    assert 0.1 * ink(plain) < ink(faded) < ink(plain), "faded, and there"
    # The graph keeps the file when the folder changes, and bench takes it too.
    monkeypatch.chdir(root)
    assert np.array_equal(pathlet.render(g, scene, time=2, size=(96, 54)).rgba, faded)
    assert _isl_stats(pathlet.bench([pathlet.Graph("isl").set("isl.color_hook=" + str(tmp_path / "my_fade.glsl"))],
                                    scene, sizes=["32x18"], frames=1, warmup=0))["segments"] > 0


def test_transparency_numbers_are_the_commands(pathlet, cli, scene):
    args = ["--time", "2:2.08:0.04", "--size", "96x54", "--transparency"]
    out = cli("quality", "variant4_opacity", *args, "--phantom", "small").stdout
    t = pathlet.quality("variant4_opacity", scene, time="2:2.08:0.04", size=(96, 54), transparency=True)
    assert f"focus visibility {t['focus_visibility']:.4f} unoccluded {t['focus_unoccluded']:.4f}" in out
    assert f"focus ink share {t['focus_ink_share']:.4f}" in out
    assert f"context coverage {t['context_coverage']:.4f}" in out
    assert f"alpha change mean {t['alpha_change_mean']:.5f} p95 {t['alpha_change_p95']:.5f}" in out
    assert f"overflow {t['overflow']}" in out
    assert 0 < t["focus_visibility"] < 1 and t["frames"] == 3 and t["located"] > 0.95 * t["fragments"]
    assert pathlet.quality("variant1_lineao", scene, time="2:2.08:0.04", size=(32, 18),
                           transparency=True)["not_measured"].startswith("no OIT")
    with pytest.raises(ValueError, match="focus share"):
        pathlet.quality("variant4_opacity", scene, time="2:2.08:0.04", size=(32, 18), transparency=True, focus_share=2)


def test_quality_against_a_reference_is_the_commands(pathlet, cli, scene, tmp_path):
    # Fidelity against a reference graph, the command's numbers; the graph's sets go to both.
    args = ["--time", "2:2.08:0.04", "--size", "96x54", "--set", "overlay=false"]
    out = cli("quality", "variant2_oit", "--reference", "variant2_exact", *args, "--phantom", "small").stdout
    g = pathlet.Graph("variant2_oit").set(overlay=False)
    q = pathlet.quality(g, scene, time="2:2.08:0.04", size=(96, 54), reference="variant2_exact", out=tmp_path)
    assert f"ssim {q['ssim']:.5f}" in out and f"rmse {q['rmse']:.5f}" in out and f"psnr {q['psnr']:.2f}" in out
    assert f"share over 8/255 {100 * q['share_over']:.4f} %" in out
    assert f"flicker vs reference {q['flicker_excess']:.5f}" in out
    assert f"flip {q['flip']:.5f} (mean LDR-FLIP over the covered pixels; all pixels {q['flip_all']:.5f};" in out
    assert q["frames"] == 3 and len(q["per_frame"]) == 3 and 0 < q["ssim"] < 0.99 and 0 < q["flip"] < 1
    assert len(q["images"]) == 8 and all(os.path.exists(f) for f in q["images"])  # diff and flip per frame
    same = pathlet.quality(g, scene, time="2:2.08:0.04", size=(96, 54), reference=g)
    assert same["ssim"] == 1.0 and same["rmse"] == 0.0 and same["flicker_excess"] == 0.0 and same["flip"] == 0.0
    # FLIP's observer as the command's --ppd: farther away (more pixels a degree), smaller errors.
    far = cli("quality", "variant2_oit", "--reference", "variant2_exact", *args, "--phantom", "small", "--ppd", "200").stdout
    q200 = pathlet.quality(g, scene, time="2:2.08:0.04", size=(96, 54), reference="variant2_exact", ppd=200)
    assert f"flip {q200['flip']:.5f} (mean LDR-FLIP over the covered pixels; all pixels {q200['flip_all']:.5f}; 200.0" in far
    assert 0 < q200["flip"] < q["flip"] and q200["ssim"] == q["ssim"]
    with pytest.raises(ValueError, match="ppd must be a positive number"):
        pathlet.quality(g, scene, time="2:2.08:0.04", size=(32, 18), reference="variant2_exact", ppd=0)
    with pytest.raises(ValueError, match="ppd needs reference="):
        pathlet.quality(g, scene, time="2:2.08:0.04", size=(32, 18), ppd=100)


def test_render_keeps_the_commands_limits(pathlet, scene):
    with pytest.raises(ValueError, match=r"ssaa must be 1\.\.8 \(got 9\)"):
        pathlet.render("variant1_lineao", scene, time=2, size=(16, 9), ssaa=9)
    with pytest.raises(ValueError, match="exceeds 16384 pixels on a side"):
        pathlet.render("variant1_lineao", scene, time=2, size=(8000, 100), ssaa=4)


def test_threads_share_the_one_context_and_the_gil_is_released(pathlet, scene):
    ref = pathlet.render("variant1_lineao", scene, time=2, size=(96, 54)).rgba
    got, errors = [], []

    def work():
        try:
            got.append(pathlet.render("variant1_lineao", scene, time=2, size=(96, 54)).rgba)
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)
    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and len(got) == 4 and all(np.array_equal(g, ref) for g in got)
    # While a long render runs, this thread keeps running Python (the GIL is not held): it spins
    # at least half as fast as alone (the clock starts before the render thread does, so time
    # spent waiting for the GIL counts).
    def spin(start_other, until):
        n, start = 0, time.perf_counter()
        start_other()
        while not until():
            n += 1
        return n / (time.perf_counter() - start), time.perf_counter() - start
    t_end = time.perf_counter() + 0.3
    alone, _ = spin(lambda: None, lambda: time.perf_counter() > t_end)
    g = pathlet.Graph("variant1_lineao")
    done = threading.Event()
    t = threading.Thread(target=lambda: (pathlet.render(g, scene, time=(0.5, 3.5, 0.1), size=(480, 270)), done.set()))
    during, seconds = spin(t.start, done.is_set)
    t.join()
    assert seconds > 0.3, "the render should take a while"
    assert during > 0.5 * alone, f"{during:.0f} loops/s while rendering, {alone:.0f} alone"


def test_use_after_close_is_an_error(root):
    code = """
import pathlet
s = pathlet.phantom("small")
pathlet.render("isl", s, time=1, size=(16, 16))
pathlet.close()
pathlet.close()
for call in (lambda: pathlet.render("isl", s, time=1, size=(16, 16)), lambda: pathlet.Graph("isl"),
             lambda: pathlet.bench(["isl"], s, sizes=["16x16"], frames=1, warmup=0)):
    try:
        call()
        print("no error")
    except pathlet.ClosedError as e:
        print("closed:", e)
print(pathlet.closed())
"""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=dict(os.environ))
    assert r.returncode == 0, r.stderr
    lines = r.stdout.strip().splitlines()
    assert len(lines) == 4 and all(l.startswith("closed: pathlet.close() was called") for l in lines[:3]), r.stdout
    assert lines[3] == "True"


def test_render_lists_the_frames_that_lost_fragments_as_the_command_does(pathlet, scene, capfd):
    # Node memory capped: every frame loses fragments, is returned anyway, and stderr's last line
    # lists them as `pathlet render`'s does.
    g = pathlet.Graph("variant2_oit").set("fill_list.max_memory_mb=0.01", window=2)
    r = pathlet.render(g, scene, time="2:2.3:0.1", size=(96, 72))
    assert r.rgba.shape[0] == 4
    err = capfd.readouterr().err.splitlines()
    assert err and err[-1] == "incomplete frames: 4 of 4 (0, 1, 2, 3)", err[-3:]
    pathlet.render("variant2_oit", scene, time="2:2.3:0.1", size=(96, 72))
    assert "incomplete frames" not in capfd.readouterr().err
