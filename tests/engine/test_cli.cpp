// The command line: exit codes (0 ok, 1 failed work, 2 bad usage), help that teaches,
// errors that name the file and place, and nothing half-written.
#include "cli_run.hpp"
#include "image_io.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

TEST(Cli, NoArgumentsPrintsOverviewAndExits2) {
    CliRun r = pathlet_cli("");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.out.find("commands:"), std::string::npos);
    EXPECT_NE(r.out.find("render"), std::string::npos);
}

TEST(Cli, HelpExitsZeroAndTeachesWithExamples) {
    for (const char* cmd : {"render", "passes", "validate", "graph", "bench"}) {
        CliRun r = pathlet_cli(std::string(cmd) + " --help");
        EXPECT_EQ(r.code, 0) << cmd;
        EXPECT_NE(r.out.find("usage: pathlet " + std::string(cmd)), std::string::npos) << cmd;
        EXPECT_NE(r.out.find("examples:"), std::string::npos) << cmd;
    }
}

TEST(Cli, UnknownCommandAndOptionExit2WithAHint) {
    EXPECT_EQ(pathlet_cli("rendr").code, 2);
    CliRun r = pathlet_cli("render --siz 10x10");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("did you mean --size"), std::string::npos) << r.err;
    r = pathlet_cli("render --size 10by10");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("WIDTHxHEIGHT"), std::string::npos) << r.err;
    r = pathlet_cli("render --time 5:1");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("END is before START"), std::string::npos) << r.err;
}

TEST(Cli, PassesListsTypesWithFilesAndDescribes) {
    CliRun r = pathlet_cli("passes");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("blur"), std::string::npos);
    EXPECT_NE(r.out.find("blur.so"), std::string::npos);
    r = pathlet_cli("passes --describe blur");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.out.find("radius (int, default 4, range [0, 64])"), std::string::npos) << r.out;
    r = pathlet_cli("passes --describe blurr");
    EXPECT_EQ(r.code, 2);  // the user's typo (issue 41)
    EXPECT_NE(r.err.find("did you mean 'blur'"), std::string::npos) << r.err;
    // --json: blur's own tmp texture is internal, not a pin a graph could bind.
    r = pathlet_cli("passes --json");
    EXPECT_EQ(r.code, 0) << r.err;
    std::string tmp_dir;
    for (const auto& t : nlohmann::json::parse(r.out))
        if (t["type"] == "blur")
            for (const auto& p : t["pins"])
                if (p["name"] == "tmp") tmp_dir = p["dir"];
    EXPECT_EQ(tmp_dir, "internal");
}

TEST(Cli, ValidateReportsEveryErrorWithPointerAndExits1) {
    fs::path bad = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_bad_graph.json";
    std::ofstream(bad) << R"({"version": 1,
      "passes": [{"name": "a", "type": "blurr", "outputs": {"dst": "x"}},
                 {"name": "b", "type": "blur", "params": {"radius": 1000}, "inputs": {"src": "nowhere"}}],
      "outputs": [{"resource": "x"}]})";
    CliRun r = pathlet_cli("validate " + bad.string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(bad.string() + ":/passes/0/type"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("did you mean 'blur'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/passes/1/params/radius"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/passes/1/inputs/src"), std::string::npos) << r.err;
    EXPECT_EQ(pathlet_cli("validate " + src("graphs/demo_blur.json")).code, 0);
}

TEST(Cli, GraphPlanAndDot) {
    CliRun r = pathlet_cli("graph " + src("graphs/demo_blur.json") + " --plan --size 64x64");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("unused"), std::string::npos);  // the culled pass is explained
    EXPECT_NE(r.out.find("line chunks 32 B per 8 segments"), std::string::npos) << r.out;  // without data: per unit
    // With data: the chunks of this data (two lines of a few points: one chunk each).
    r = pathlet_cli("graph " + src("graphs/demo_blur.json") + " --plan --size 64x64 --data " +
                    src("tests/engine/data/two_lines.vtk"));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("2 lines"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(", 2 line chunks"), std::string::npos) << r.out;
    fs::path dot = fs::path(PATHLET_TEST_BINARY_DIR) / "demo.dot";
    fs::remove(dot);
    r = pathlet_cli("graph " + src("graphs/demo_blur.json") + " --dot " + dot.string());
    EXPECT_EQ(r.code, 0) << r.err;
    std::ifstream in(dot);
    std::string first;
    std::getline(in, first);
    EXPECT_NE(first.find("digraph"), std::string::npos);
}

TEST(Cli, RenderWritesImagesAndTimingTable) {
    fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_render";
    fs::remove_all(out);
    CliRun r = pathlet_cli("render " + src("graphs/demo_blur.json") + " --data " + src("tests/engine/data/two_lines.vtk") +
                    " --time 0:1:0.5 --size 48x32 --out " + out.string() + " --quiet --report " +
                    (out / "timing").string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "demo_blur" / "00000.png"));
    EXPECT_TRUE(fs::exists(out / "demo_blur" / "00002.png"));
    EXPECT_TRUE(fs::exists(out / "timing.trace.json"));
    EXPECT_NE(r.out.find("soft"), std::string::npos) << r.out;  // the blur pass has a row
    // No temporary files are left behind.
    for (const auto& e : fs::recursive_directory_iterator(out))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(Cli, RenderWithMissingDataFailsWith1AndAMissingGraphWith2) {
    CliRun r = pathlet_cli("render " + src("graphs/demo_blur.json") + " --data /no/such/file.vtk --quiet");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/no/such/file.vtk"), std::string::npos) << r.err;
    r = pathlet_cli("render /no/such/graph.json --data " + src("tests/engine/data/two_lines.vtk") + " --quiet");
    EXPECT_EQ(r.code, 2) << "a graph that is not there is the user's mistake (issue 41)";
    EXPECT_EQ(r.err.rfind("error: no graph '/no/such/graph.json'", 0), 0u) << r.err;
}

TEST(Cli, BadSetOverrideIsReported) {
    CliRun r = pathlet_cli("render " + src("graphs/demo_blur.json") + " --data " + src("tests/engine/data/two_lines.vtk") +
                    " --set soft.radiuss=2 --no-images --quiet --time 0");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("radius"), std::string::npos) << r.err;  // did you mean
}

TEST(Cli, PhantomTraceAndInfoRoundTrip) {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_data";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string lines = (dir / "small.vtp").string(), wall = (dir / "small.glb").string();
    CliRun r = pathlet_cli("phantom --preset small -o " + lines + " --wall " + wall);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(lines));
    EXPECT_TRUE(fs::exists(wall));
    r = pathlet_cli("info " + lines);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("lines:"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("time (1 comp)"), std::string::npos) << r.out;
    r = pathlet_cli("info " + wall);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("triangles"), std::string::npos) << r.out;
    // The traced file renders, with its wall loaded.
    r = pathlet_cli("render isl --data " + lines + " --mesh " + wall + " --time 1 --size 32x24 --no-images --quiet");
    EXPECT_EQ(r.code, 0) << r.err;
}

TEST(Cli, DataCommandsRejectBadInputWithExitCodes) {
    const std::string scratch = (fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs").string();
    EXPECT_EQ(pathlet_cli("phantom --preset huge -o " + scratch + "/x.vtp").code, 2);
    EXPECT_EQ(pathlet_cli("phantom --preset small").code, 2);  // no output
    CliRun r = pathlet_cli("phantom --preset small -o " + (fs::path(PATHLET_TEST_BINARY_DIR) / "x.txt").string());
    EXPECT_EQ(r.code, 1);  // unknown output extension: a clear error, nothing written
    EXPECT_NE(r.err.find("x.txt"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(fs::path(PATHLET_TEST_BINARY_DIR) / "x.txt"));
    r = pathlet_cli("trace /no/such/field.vtk -o " + scratch + "/y.vtp");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/no/such/field.vtk"), std::string::npos) << r.err;
    fs::path bad = fs::path(PATHLET_TEST_BINARY_DIR) / "truncated.vtk";
    std::ofstream(bad) << "# vtk DataFile Version 4.2\nx\nASCII\nDATASET POLYDATA\nPOINTS 10 float\n0 0 0 1 1";
    r = pathlet_cli("info " + bad.string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
}

TEST(Cli, UnitsOptionAndTractsAsAUserUsesThem) {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_tracts";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string rows = (dir / "rows.txt").string();
    std::ofstream(rows) << "0 0 0 1 0 0 2 0 1\n0 1 0 1 1 0 2 1 1 3 1 2\n";
    CliRun r = pathlet_cli("info " + rows + " --units mm --time-step 0.5");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("units:     length mm, time s, velocity mm/s"), std::string::npos) << r.out;
    for (const char* bad : {"a,b,c", ",", "'x y '"}) {
        r = pathlet_cli("info " + rows + " --units " + bad);
        EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
        EXPECT_NE(r.err.find("--units"), std::string::npos) << r.err;
    }
    EXPECT_EQ(pathlet_cli("render --data " + rows + " --units a,b,c --no-images --quiet").code, 2);
    // A .tck renders as one frame of whole lines without --time; --pseudo-time animates it.
    const std::string tck = (dir / "t.tck").string();
    {
        std::ofstream f(tck, std::ios::binary);
        f << "mrtrix tracks\ndatatype: Float32LE\nfile: . 49\nEND\n";  // 49 bytes of header
        const float v[] = {0, 0, 0, 10, 0, 0, 10, 5, 0, NAN, NAN, NAN, 0, 5, 0, 0, 5, 8, NAN, NAN, NAN, INFINITY, INFINITY, INFINITY};
        f.write(reinterpret_cast<const char*>(v), sizeof v);
    }
    r = pathlet_cli("render tracts_lineao --data " + tck + " --size 64x36 --quiet --out " + (dir / "out").string());
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "out" / "tracts_lineao" / "00000.png"));
    EXPECT_FALSE(fs::exists(dir / "out" / "tracts_lineao" / "00001.png")) << "whole lines: one frame";
    r = pathlet_cli("render --data " + tck + " --pseudo-time --size 64x36 --no-images --quiet");
    EXPECT_EQ(r.code, 0) << r.err;
    r = pathlet_cli("info " + tck + " --pseudo-time");
    EXPECT_NE(r.out.find("time:      0 .. "), std::string::npos) << r.out;
}

TEST(Cli, EveryShippedGraphValidates) {
    std::string files;
    for (const auto& e : fs::directory_iterator(src("graphs")))
        if (e.path().extension() == ".json") files += " " + e.path().string();
    ASSERT_FALSE(files.empty());
    CliRun r = pathlet_cli("validate" + files);
    EXPECT_EQ(r.code, 0) << r.err;
    for (const char* g : {"variant1_lineao", "isl", "lineao_debug", "gbuffer_only", "demo_blur"})
        EXPECT_NE(r.out.find(std::string(g) + ".json: ok"), std::string::npos) << g;
}

TEST(Cli, CaptureWithoutExtensionPicksExrForFloatAndPngOtherwise) {
    fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_capture_formats";
    fs::remove_all(out);
    CliRun r = pathlet_cli("render " + src("tests/engine/graphs/capture_formats.json") + " --data " +
                       src("tests/engine/data/two_lines.vtk") + " --time 0 --size 24x16 --quiet --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "blurred_000.png"));
    EXPECT_TRUE(fs::exists(out / "soft.tmp_000.exr"));  // the blur's rgba16f intermediate
}

TEST(Cli, OutputPlacesAreCheckedBeforeAnyWork) {
    // A folder that cannot be created: the error names it and comes before GL or data loading.
    CliRun r = pathlet_cli("render --out /proc/pathlet_no_such --time 1 --size 32x24");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/proc/pathlet_no_such"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("GL renderer"), std::string::npos) << "failed only after GL set-up:\n" << r.err;
    EXPECT_EQ(r.err.find("lines in"), std::string::npos) << "failed only after loading data:\n" << r.err;
    // --out naming a file, --report and --video into impossible places.
    fs::path file = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs" / "a_file.txt";
    std::ofstream(file) << "x";
    r = pathlet_cli("render --out " + file.string() + " --time 1 --size 32x24");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("not a folder"), std::string::npos) << r.err;
    r = pathlet_cli("render --no-images --report /proc/none/t --time 1 --size 32x24");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("--report"), std::string::npos) << r.err;
    r = pathlet_cli("bench isl --report /proc/none/b --size 32x24 --frames 1 --warmup 0");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/proc/none"), std::string::npos) << r.err;
    // phantom and trace: before tracing.
    r = pathlet_cli("phantom --preset small -o /proc/none/p.vtp");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/proc/none"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("tracing"), std::string::npos) << "failed only after tracing:\n" << r.err;
    r = pathlet_cli("phantom --preset small -o " + (fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs" / "p.vtp").string() +
                " --wall /proc/none/w.glb");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/proc/none/w.glb"), std::string::npos) << r.err;
}

TEST(Cli, BadSizesAndDirectoriesAreClearErrors) {
    for (const char* size : {"0x0", "-5x10", "100000x100000", "axb"}) {
        CliRun r = pathlet_cli(std::string("render --size ") + size + " --no-images");
        EXPECT_EQ(r.code, 2) << size;
        EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
    }
    for (const char* ssaa : {"0", "9", "x", "4 --size 8000x100"}) {
        CliRun r = pathlet_cli(std::string("render --ssaa ") + ssaa + " --no-images");
        EXPECT_EQ(r.code, 2) << ssaa;
        EXPECT_NE(r.err.find("ssaa"), std::string::npos) << r.err;
    }
    CliRun r = pathlet_cli("validate " + std::string(PATHLET_TEST_BINARY_DIR));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
    r = pathlet_cli("info " + std::string(PATHLET_TEST_BINARY_DIR));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
}

TEST(Cli, PathsWithSpacesAndNonUtf8BytesWork) {
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs" / "with space \xff\xfe dir";
    fs::remove_all(dir);
    CliRun r = pathlet_cli("render isl --data '" + src("tests/engine/data/two_lines.vtk") + "' --out '" + dir.string() +
                       "' --time 0.5 --size 32x24 --quiet");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir / "isl" / "00000.png"));
    fs::remove_all(dir);
}

TEST(Cli, BenchSetsCanTargetOneGraph) {
    const std::string common = " --data " + src("tests/engine/data/two_lines.vtk") + " --time 0.5 --size 32x24 --frames 1 --warmup 0";
    // The same graph twice, set differently: both rows, labelled.
    CliRun r = pathlet_cli("bench isl,isl --set 2:window=0" + common);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("isl [window=0]"), std::string::npos) << r.out;
    // A parameter only one graph has, given to that graph only.
    r = pathlet_cli("bench isl,variant3_geomfade --set variant3_geomfade:tail_fade=0.2" + common);
    EXPECT_EQ(r.code, 0) << r.err;
    r = pathlet_cli("bench isl,variant3_geomfade --set tail_fade=0.2" + common);
    EXPECT_EQ(r.code, 1) << "unqualified: every graph must have it";
    // A qualifier naming no listed graph: a usage error before any work.
    r = pathlet_cli("bench isl --set 3:window=0" + common);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("none of the graphs"), std::string::npos) << r.err;
}

TEST(Cli, NoEglIsAClearErrorNotACrash) {
    // glvnd with no vendor library: no EGL implementation at all.
    CliRun r = pathlet_cli("render --time 1 --size 32x24 --no-images --quiet", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("cannot create a headless OpenGL 4.5 context"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not offered"), std::string::npos) << "says what was tried:\n" << r.err;
    EXPECT_NE(r.err.find("Install Mesa"), std::string::npos) << r.err;
}

TEST(Cli, KilledMidRenderLeavesOnlyCompleteFiles) {
    // Frames are written to a hidden temporary name and renamed: a SIGKILL at any moment
    // leaves complete PNGs under their final names; the next render clears the stale temps.
    fs::path dir = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_runs" / "killed";
    fs::remove_all(dir);
    // Killed once its first frame is on disk (however slow the machine), mid-way through later ones.
    const std::string cmd = "bash -c '" + std::string(PATHLET_CLI) + " render isl --data " +
                            src("tests/engine/data/two_lines.vtk") + " --time 0:1000:0.01 --allow-empty-frames --size 320x240 --quiet --out " +
                            dir.string() + " >/dev/null 2>&1 & pid=$!; for i in $(seq 1200); do " +
                            "ls " + dir.string() + "/isl/*.png >/dev/null 2>&1 && break; sleep 0.1; done; sleep 0.5; " +
                            "kill -KILL $pid; wait $pid'";
    int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 137) << "the render should have been killed";
    size_t complete = 0;
    for (const auto& e : fs::directory_iterator(dir / "isl")) {
        const std::string name = e.path().filename().string();
        if (name[0] == '.') continue;  // a temp of the killed process
        pathlet::Image img = pathlet::read_image(e.path().string());
        EXPECT_EQ(img.width, 320) << name;
        ++complete;
    }
    EXPECT_GT(complete, 0u);
    CliRun r = pathlet_cli("render isl --data " + src("tests/engine/data/two_lines.vtk") + " --time 0 --size 32x24 --quiet --out " +
                       dir.string());
    EXPECT_EQ(r.code, 0) << r.err;
    for (const auto& e : fs::directory_iterator(dir / "isl"))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << "stale temp left: " << e.path();
    fs::remove_all(dir);
}

TEST(Cli, EveryCommandDeclaresItsOptionsOnce) {
    // A command's options are declared when it runs: --help builds every declaration, so a
    // name declared twice (say, a shared block and the command's own) fails here (exit 70).
    CliRun overview = pathlet_cli("--help");
    ASSERT_EQ(overview.code, 0);
    std::istringstream in(overview.out.substr(overview.out.find("commands:\n") + 10));
    size_t commands = 0;
    for (std::string line; std::getline(in, line) && line.rfind("  ", 0) == 0;) {
        const std::string cmd = line.substr(2, line.find(' ', 2) - 2);
        CliRun r = pathlet_cli(cmd + " --help");
        EXPECT_EQ(r.code, 0) << cmd << ": " << r.err;
        EXPECT_EQ(r.out.rfind("usage: pathlet " + cmd, 0), 0u) << r.out;
        ++commands;
    }
    EXPECT_GE(commands, 10u);
}

TEST(Cli, MalformedOptionValuesAreUsageErrorsNamingTheOption) {
    const std::string data = " --data " + src("tests/engine/data/two_lines.vtk");
    struct Case {
        std::string args, want;
    } cases[] = {
        {"view --time x" + data, "--time expects a number, got 'x'"},  // was "error: stod"
        {"render --warmup 2.5 --no-images" + data, "--warmup expects an integer, got '2.5'"},
        {"render --orbit fast --no-images" + data, "--orbit expects a number, got 'fast'"},
        {"render --timing fastest --no-images" + data, "--timing expects auto, gpu, finish or cpu, got 'fastest'"},
        {"bench isl --frames many" + data, "--frames expects an integer, got 'many'"},
        {"bench isl --threshold 0.1x --compare x.json" + data, "--threshold expects a number, got '0.1x'"},
        {"trace f.vtk -o f.vtp --step 1/4", "--step expects a number, got '1/4'"},
        {"phantom -o x.vtp --threads all", "--threads expects an integer, got 'all'"},
        {"info f.vtk --time-step -1", "--time-step must be >= 0"},
        {"graph isl --size 10", "--size '10': expected WIDTHxHEIGHT"},
        {"quality --rays 1e3.5", "--rays expects an integer, got '1e3.5'"},
        {"validate", "missing GRAPH"},
        {"passes --plugin", "unknown option --plugin (did you mean --plugin-dir?)"},
    };
    for (const auto& c : cases) {
        CliRun r = pathlet_cli(c.args);
        EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.want), std::string::npos) << c.args << "\nwant: " << c.want << "\n" << r.err;
        EXPECT_NE(r.err.find("--help"), std::string::npos) << "points at the help:\n" << r.err;
        EXPECT_EQ(r.err.find("stod"), std::string::npos) << r.err;
    }
}

// Passes or parameters that must agree and do not: the graph is refused when it compiles, before
// any GL or frame, naming both (a graph error: exit 1, as every graph error). MBOIT's
// accumulation reading trigonometric moments from power moments; opacity_resolve's
// clamp(x, adapt_min, adapt_max), undefined in GLSL for adapt_min > adapt_max.
TEST(Cli, ValuesThatMustAgreeAndDoNotAreRefusedNamingBoth) {
    const fs::path out = fs::path(PATHLET_TEST_BINARY_DIR) / "cli_disagree_out";
    fs::remove_all(out);
    const std::string common = " --phantom small --time 2 --size 32x18 --out " + out.string();
    CliRun r = pathlet_cli("render variant2_mboit8 --set accum.moment_form=trig4" + common);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("pass 'accum' (mboit_accum) has moment_form = trig4 but pass 'moments' (mboit_moments)"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("moment_form = power8"), std::string::npos) << r.err;
    r = pathlet_cli("render variant2_mboit8 --set moments.moment_form=power4" + common);
    EXPECT_EQ(r.code, 1) << "accum at power8 would read moments_high nobody wrote\n" << r.err;
    r = pathlet_cli("render variant4_opacity --set opacity_resolve.adapt_min=8" + common);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("adapt_min = 8 is above adapt_max = 4"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out) && !fs::is_empty(out)) << "no frame before the graph is known good";
    // Agreeing values render (the graph variable feeds both passes).
    r = pathlet_cli("render variant2_mboit8 --set moments=trig4 --no-images --quiet --phantom small --time 2 --size 32x18");
    EXPECT_EQ(r.code, 0) << r.err;
}
