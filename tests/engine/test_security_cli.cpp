// Opening a graph, experiment or data file never runs code or reads files the user did not
// choose (issue 23), run as a user would. The plugin folder a graph names holds a plugin whose
// constructor writes a marker file: where the folder is not trusted, the marker must not appear.
// Every run points XDG_CONFIG_HOME at a scratch folder: no test touches the real ~/.config.
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <fstream>
#include <sstream>

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Security : ::testing::Test {
    fs::path root, config, plugins, marker;

    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        root = fs::path(PATHLET_TEST_BINARY_DIR) / "security_runs" / info->name();
        fs::remove_all(root);
        config = root / "config";
        plugins = root / "plugins";
        marker = root / "constructor_ran.txt";
        fs::create_directories(config);
        plugin_folder(plugins);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(root);
    }
    // A folder holding the marker plugin (a valid plugin whose constructor writes `marker`).
    void plugin_folder(const fs::path& dir) {
        fs::create_directories(dir);
        fs::permissions(dir, fs::perms(0755));
        fs::copy_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_marker_pass.so", dir / "pathlet_marker.so",
                      fs::copy_options::overwrite_existing);
    }
    // A graph beside `root` whose only pass comes from the plugin folder it names.
    fs::path graph(const std::string& name, const std::string& plugin_dir) {
        const fs::path g = root / name;
        std::ofstream(g) << R"({"version": 1, "plugin_dirs": [")" << plugin_dir << R"("],
          "passes": [{"name": "m", "type": "fixture_marker"}], "outputs": [{"resource": "m.color"}]})";
        return g;
    }
    std::string env(const std::string& more = "") const {
        return "XDG_CONFIG_HOME='" + config.string() + "' PATHLET_FIXTURE_MARKER='" + marker.string() + "' " + more;
    }
    CliRun run(const std::string& args, const std::string& more_env = "") const { return pathlet_cli(args, env(more_env)); }
    bool constructor_ran() const { return fs::exists(marker); }
    fs::path trust_file() const { return config / "pathlet" / "trusted-plugin-dirs"; }
};

const std::string kData = " --data " + src("tests/engine/data/two_lines.vtk") + " --time 0 --size 32x24";

}  // namespace

TEST_F(Security, AnUntrustedGraphFolderIsNeverOpened) {
    const fs::path g = graph("g.json", "plugins");
    const std::string canonical = fs::canonical(plugins).string();
    for (const std::string& args : {"graph " + g.string() + " --plan", "render " + g.string() + " --no-images --quiet" + kData,
                                   "bench " + g.string() + " --frames 1 --warmup 0 --quiet" + kData}) {
        CliRun r = run(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
        EXPECT_FALSE(constructor_ran()) << args << ": the untrusted plugin's constructor ran";
        // The graph, the folder, the plugin files and the exact command that trusts it.
        EXPECT_NE(r.err.find(g.string() + ":/plugin_dirs/0"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("plugin folder " + canonical + " is not trusted"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(canonical + "/pathlet_marker.so"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("pathlet trust " + canonical), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("GL renderer"), std::string::npos) << "stopped only after GL set-up:\n" << r.err;
    }
    EXPECT_FALSE(fs::exists(trust_file())) << "nothing trusted by running";
}

TEST_F(Security, ValidateNamesTypesOfAnUntrustedFolderWithoutOpeningIt) {
    const fs::path g = graph("g.json", "plugins");
    CliRun r = run("validate " + g.string());
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_FALSE(constructor_ran());
    EXPECT_NE(r.err.find(g.string() + ":/passes/0/type: unknown pass type 'fixture_marker'; it may come from the "
                                      "graph's plugin folder " + fs::canonical(plugins).string()),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("not loaded because it is not trusted: pathlet trust "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << "reported as a typo:\n" << r.err;
}

TEST_F(Security, TrustedThroughTheTrustFile) {
    const fs::path g = graph("g.json", "plugins");
    CliRun r = run("trust " + plugins.string());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(trust_file()).find(fs::canonical(plugins).string() + "\n") != std::string::npos, true)
        << slurp(trust_file());
    struct stat st {};
    ASSERT_EQ(::stat(trust_file().c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0077, 0u) << "the trust file is the user's alone";
    r = run("trust");
    EXPECT_NE(r.out.find(fs::canonical(plugins).string()), std::string::npos) << r.out;
    r = run("graph " + g.string() + " --plan");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(constructor_ran()) << "trusted: the plugin is loaded";
    fs::remove(marker);
    EXPECT_EQ(run("trust --remove " + plugins.string()).code, 0);
    r = run("graph " + g.string() + " --plan");
    EXPECT_EQ(r.code, 1) << "no longer trusted";
    EXPECT_FALSE(constructor_ran());
    EXPECT_EQ(run("trust --remove " + plugins.string()).code, 1) << "not in the list any more";
}

TEST_F(Security, TrustedForOneRunByTheFlagOrBecauseTheUserNamedTheFolder) {
    const fs::path g = graph("g.json", "plugins");
    EXPECT_EQ(run("graph " + g.string() + " --plan --trust-graph-plugins").code, 0);
    EXPECT_TRUE(constructor_ran());
    EXPECT_EQ(run("validate " + g.string() + " --trust-graph-plugins").code, 0);
    EXPECT_EQ(run("graph " + g.string() + " --plan --plugin-dir " + plugins.string()).code, 0);
    EXPECT_EQ(run("graph " + g.string() + " --plan", "PATHLET_PLUGIN_PATH='" + plugins.string() + "'").code, 0);
    EXPECT_FALSE(fs::exists(trust_file()));
}

TEST_F(Security, TrustFollowsTheFolderNotItsNameSymlinksAndDotDot) {
    // A trusted folder does not lend its trust to "trusted/../elsewhere".
    fs::create_directories(root / "trusted");
    fs::permissions(root / "trusted", fs::perms(0755));
    ASSERT_EQ(run("trust " + (root / "trusted").string()).code, 0);
    CliRun r = run("graph " + graph("dotdot.json", "trusted/../plugins").string() + " --plan");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("plugin folder " + fs::canonical(plugins).string() + " is not trusted"), std::string::npos)
        << r.err;
    EXPECT_FALSE(constructor_ran());
    // Trusting a link trusts the folder it points at (canonical path), not the link: pointed
    // elsewhere later, the link is not trusted.
    fs::create_directory_symlink(plugins, root / "link");
    ASSERT_EQ(run("trust " + (root / "link").string()).code, 0);
    EXPECT_EQ(slurp(trust_file()).find((root / "link").string()), std::string::npos) << slurp(trust_file());
    plugin_folder(root / "elsewhere");
    fs::remove(root / "link");
    fs::create_directory_symlink(root / "elsewhere", root / "link");
    r = run("graph " + graph("link.json", "link").string() + " --plan");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(fs::canonical(root / "elsewhere").string() + " is not trusted"), std::string::npos) << r.err;
    EXPECT_FALSE(constructor_ran());
    EXPECT_EQ(run("graph " + graph("direct.json", "plugins").string() + " --plan").code, 0) << "the folder itself is";
}

TEST_F(Security, WorldWritableFoldersAreNeverTrustedOrLoaded) {
    fs::permissions(plugins, fs::perms(0777));
    CliRun r = run("trust " + plugins.string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("world-writable"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(trust_file()));
    // Trusted first, made world-writable later: refused when loading.
    fs::permissions(plugins, fs::perms(0755));
    ASSERT_EQ(run("trust " + plugins.string()).code, 0);
    fs::permissions(plugins, fs::perms(0777));
    r = run("graph " + graph("g.json", "plugins").string() + " --plan");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("plugin folder is world-writable"), std::string::npos) << r.err;
    EXPECT_FALSE(constructor_ran());
}

TEST_F(Security, ATrustFileOthersCanWriteIsNotBelieved) {
    ASSERT_EQ(run("trust " + plugins.string()).code, 0);
    fs::permissions(trust_file(), fs::perms(0666));
    CliRun r = run("graph " + graph("g.json", "plugins").string() + " --plan");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("can be changed by other users"), std::string::npos) << r.err;
    EXPECT_FALSE(constructor_ran());
    fs::permissions(trust_file(), fs::perms(0620));  // the group may write it: not believed either
    r = run("graph " + graph("g.json", "plugins").string() + " --plan");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("group-writable"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(trust_file().string()), std::string::npos) << "names the file: " << r.err;
    EXPECT_FALSE(constructor_ran());
}

TEST_F(Security, TheTrustFileLivesInXdgConfigHomeElseHomeConfig) {
    const fs::path home = root / "home";
    fs::create_directories(home);
    EXPECT_EQ(pathlet_cli("trust " + plugins.string(), "XDG_CONFIG_HOME= HOME='" + home.string() + "'").code, 0);
    EXPECT_TRUE(fs::exists(home / ".config" / "pathlet" / "trusted-plugin-dirs"));
    EXPECT_FALSE(fs::exists(trust_file()));
}

TEST_F(Security, AnExperimentNamingAnUntrustedFolderStopsBeforeAnyRun) {
    graph("g.json", "plugins");
    const fs::path e = root / "e.json";
    std::ofstream(e) << R"({"graphs": ["g.json", "isl"], "data": [{"phantom": "small"}], "sizes": ["32x24"], "frames": 1})";
    // Graphs of an experiment are named relative to the working folder, as on the command line.
    CliRun r = pathlet_cli("bench --experiment " + e.string() + " --out " + (root / "out").string(),
                           "cd '" + root.string() + "' && " + env());
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("is not trusted"), std::string::npos) << r.err;
    EXPECT_FALSE(constructor_ran());
    EXPECT_FALSE(fs::exists(root / "out" / "results.json")) << "a run happened";
}

TEST_F(Security, APluginOfAnotherSdkIsRefusedWithRebuild) {
    fs::create_directories(root / "old");
    fs::copy_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_old_sdk.so", root / "old" / "pathlet_old.so");
    CliRun r = run("passes --plugin-dir " + (root / "old").string());
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("rebuild against this SDK"), std::string::npos) << r.err;
    EXPECT_FALSE(constructor_ran());
}

TEST_F(Security, ShaderNamesResolveOnlyOnTheShaderPath) {
    for (const std::string& name : std::vector<std::string>{"/etc/passwd", "../../../../../../etc/passwd", "sub/gradient.frag", ".."}) {
        const fs::path g = root / "shader.json";
        std::ofstream(g) << R"({"version": 1, "passes": [{"name": "p", "type": "fullscreen", "params": {"shader": ")"
                         << name << R"("}}], "outputs": [{"resource": "p.color"}]})";
        CliRun r = run("render " + g.string() + " --no-images --quiet" + kData);
        EXPECT_EQ(r.code, 1) << name << "\n" << r.err;
        EXPECT_NE(r.err.find("shader name '" + name + "' refused: a shader is a file name"), std::string::npos) << r.err;
    }
}

TEST_F(Security, AnEmptyDataSetIsAnErrorNamingTheFileAndTheRepair) {
    // Two "lines" of one point each: the repair drops both, nothing is left to draw.
    const fs::path data = root / "points.txt";
    std::ofstream(data) << "0 0 0\n1 1 1\n";
    const std::string args = " --data " + data.string() + " --time 0 --size 32x24";
    for (const std::string& cmd : std::vector<std::string>{"render --no-images --quiet", "bench isl --frames 1 --warmup 0 --quiet"}) {
        CliRun r = run(cmd + args);
        EXPECT_EQ(r.code, 1) << cmd << "\n" << r.err;
        EXPECT_NE(r.err.find(data.string() + ": no line to draw after repair (dropped 2 lines with fewer than 2"),
                  std::string::npos)
            << r.err;
    }
    CliRun r = run("info " + data.string());
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("lines:"), std::string::npos) << "info still shows the numbers:\n" << r.out;
}

// A downloaded graph named "../escape" must not write beside the output folder through {graph}
// (render), quality --out or the output-folder record: every command refuses it by name (a graph
// error, exit 1), and nothing appears outside --out.
TEST_F(Security, AGraphNameThatClimbsOutOfTheOutputFolderIsRefused) {
    const fs::path g = root / "escape.json";
    std::ofstream(g) << R"({"version": 1, "extends": "variant2_exact", "name": "../escape"})";
    const fs::path out = root / "outdir" / "o";
    fs::create_directories(out);
    for (const std::string& args :
         {"render " + g.string() + " --out " + out.string() + kData,
          "quality " + g.string() + " --reference variant2_exact --out " + out.string() + kData}) {
        CliRun r = run(args);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("/name: graph name '../escape' must not contain '/'"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(root / "outdir" / "escape")) << args;
        EXPECT_TRUE(fs::is_empty(out)) << args << ": nothing written for a refused graph";
    }
}
