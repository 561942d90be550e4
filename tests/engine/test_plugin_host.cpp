// Every plugin-host failure gives a message naming the file and the reason, and leaves the
// registry as it was. The fixture plugins are built next to this test.
#include "plugin_elf.hpp"
#include "plugin_host.hpp"

#include <pathlet/plugin.hpp>

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {

struct Nop : Pass {
    void execute(PassContext&) override {}
};

std::string fixture(const std::string& name) { return std::string(PATHLET_FIXTURE_DIR) + "/pathlet_" + name + ".so"; }

std::string load_error(PluginHost& host, const std::string& path) {
    try {
        host.load_file(path);
    } catch (const PluginError& e) {
        return e.what();
    }
    return "";
}

struct PluginHostTest : ::testing::Test {
    PassRegistry reg;
    PluginHost host{reg};
    void expect_failure(const std::string& path, const std::string& reason) {
        size_t before = reg.all().size();
        std::string msg = load_error(host, path);
        EXPECT_EQ(msg.rfind(path, 0), 0u) << "message must start with the file: " << msg;
        EXPECT_NE(msg.find(reason), std::string::npos) << msg;
        EXPECT_EQ(reg.all().size(), before) << "a failed plugin must register nothing";
    }
};

TEST_F(PluginHostTest, GoodPluginRegistersItsTypes) {
    host.load_file(fixture("good_pass"));
    ASSERT_NE(reg.find("fixture_throw"), nullptr);
    EXPECT_EQ(reg.find("fixture_throw")->plugin_file, fixture("good_pass"));
    ASSERT_EQ(host.loaded().size(), 1u);
    EXPECT_EQ(host.loaded()[0].types.size(), 2u);
}

TEST_F(PluginHostTest, MissingFile) { expect_failure(fixture("no_such_plugin"), "file not found"); }

TEST_F(PluginHostTest, NotASharedLibrary) {
    fs::path p = fs::temp_directory_path() / ("pathlet_text_file_" + std::to_string(::getpid()) + ".so");
    std::ofstream(p) << "this is not an ELF file\n";
    expect_failure(p.string(), "not a Pathlet plugin (not an ELF file); never opened");
}

TEST_F(PluginHostTest, NotAPlugin) { expect_failure(fixture("not_a_plugin"), "not a Pathlet plugin"); }

TEST_F(PluginHostTest, AbiVersionMismatch) { expect_failure(fixture("bad_abi"), "ABI version 99"); }

TEST_F(PluginHostTest, BuildFingerprintMismatch) { expect_failure(fixture("bad_fingerprint"), "different compiler"); }

TEST_F(PluginHostTest, UnresolvedSymbolFailsAtLoadNotAtCall) {
    // RTLD_NOW reports dlerror() verbatim, which names the symbol.
    expect_failure(fixture("missing_symbol"), "pathlet_function_that_does_not_exist");
}

TEST_F(PluginHostTest, ExceptionWhileRegistering) {
    expect_failure(fixture("throws_on_register"), "cannot register today");
}

TEST_F(PluginHostTest, DuplicateTypeNameNamesBothFiles) {
    PassTypeInfo t = PassTypeBuilder("blur", "first").output_texture("dst", "rgba8", "x").make<Nop>();
    t.plugin_file = "/first/blur.so";
    reg.add(t);
    std::string msg = load_error(host, fixture("duplicate_type"));
    EXPECT_NE(msg.find("'blur' is already registered by /first/blur.so"), std::string::npos) << msg;
    EXPECT_EQ(reg.find("blur")->doc, "first");
}

TEST_F(PluginHostTest, DirectoryScanCollectsProblemsAndKeepsGoing) {
    host.load_dirs({PATHLET_FIXTURE_DIR});
    EXPECT_NE(reg.find("fixture_throw"), nullptr);  // the good one still loads
    // bad_abi, bad_fingerprint, not_a_plugin, missing_symbol, throws_on_register
    EXPECT_GE(host.problems().size(), 5u);
    for (const auto& p : host.problems()) EXPECT_EQ(p.rfind(PATHLET_FIXTURE_DIR, 0), 0u) << p;
}

TEST(PluginSearchPath, EnvironmentAndExtraDirsComeFirst) {
    ::setenv("PATHLET_PLUGIN_PATH", "/env/a:/env/b", 1);
    auto dirs = PluginHost::search_path({"/extra"});
    ::unsetenv("PATHLET_PLUGIN_PATH");
    ASSERT_GE(dirs.size(), 4u);
    EXPECT_EQ(dirs[0], "/extra");
    EXPECT_EQ(dirs[1], "/env/a");
    EXPECT_EQ(dirs[2], "/env/b");
    EXPECT_NE(dirs.back().find("pathlet/passes"), std::string::npos);
}

// ---- checks before a file is opened --------------------------------------------

// A fresh folder for one test, and a marker file the fixtures' constructors write when (and
// only when) a library is loaded.
struct LoadScratch : ::testing::Test {
    fs::path dir, marker;
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::path(PATHLET_TEST_BINARY_DIR) / "plugin_scratch" / info->name();
        fs::remove_all(dir);
        fs::create_directories(dir / "plugins");
        fs::permissions(dir / "plugins", fs::perms(0755));
        marker = dir / "constructor_ran.txt";
        ::setenv("PATHLET_FIXTURE_MARKER", marker.c_str(), 1);
    }
    void TearDown() override {
        ::unsetenv("PATHLET_FIXTURE_MARKER");
        fs::remove_all(dir);
    }
    fs::path put(const std::string& fixture_name, const std::string& as) {
        const fs::path p = dir / "plugins" / as;
        fs::copy_file(fixture(fixture_name), p);
        fs::permissions(p, fs::perms(0755));
        return p;
    }
    bool constructor_ran() const { return fs::exists(marker); }
};

std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += x + "\n";
    return s;
}

TEST_F(LoadScratch, TheMarkerFixtureProvesALoadRunsConstructors) {
    // The check the other tests rely on: loading the marker plugin does write the file.
    PassRegistry reg;
    PluginHost host(reg);
    host.load_file(put("marker_pass", "pathlet_marker.so").string());
    EXPECT_NE(reg.find("fixture_marker"), nullptr);
    EXPECT_TRUE(constructor_ran());
}

TEST_F(LoadScratch, AFileWithoutTheEntryPointIsNeverOpened) {
    PassRegistry reg;
    PluginHost host(reg);
    const fs::path p = put("not_a_plugin", "pathlet_not_a_plugin.so");
    const std::string msg = load_error(host, p.string());
    EXPECT_NE(msg.find("no pathlet_plugin_v1 entry point"), std::string::npos) << msg;
    EXPECT_NE(msg.find("never opened"), std::string::npos) << msg;
    EXPECT_FALSE(constructor_ran()) << "dlopen ran the library's constructor";
}

TEST_F(LoadScratch, APluginOfAnotherSdkIsRefusedBeforeLoading) {
    PassRegistry reg;
    PluginHost host(reg);
    std::string msg = load_error(host, put("old_sdk", "pathlet_old_sdk.so").string());
    EXPECT_NE(msg.find("built against another SDK (fingerprint 0123456789abcdef)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("this engine's SDK is " PATHLET_SDK_FINGERPRINT), std::string::npos) << msg;
    EXPECT_NE(msg.find("rebuild against this SDK"), std::string::npos) << msg;
    msg = load_error(host, put("no_sdk", "pathlet_no_sdk.so").string());
    EXPECT_NE(msg.find("built against an older SDK (no SDK fingerprint)"), std::string::npos) << msg;
    EXPECT_FALSE(constructor_ran());
    EXPECT_TRUE(reg.all().empty());
}

TEST_F(LoadScratch, OtherFilesInAPluginFolderAreSkippedWithANote) {
    put("marker_pass", "libmarker.so");        // a library not named like a plugin
    put("good_pass", "pathlet_good_pass.so");  // a plugin
    std::ofstream(dir / "plugins" / "README.txt") << "notes\n";
    PassRegistry reg;
    PluginHost host(reg);
    host.load_dirs({(dir / "plugins").string()});
    EXPECT_NE(reg.find("fixture_throw"), nullptr) << joined(host.problems());
    EXPECT_EQ(reg.find("fixture_marker"), nullptr);
    ASSERT_EQ(host.notes().size(), 1u) << joined(host.notes());
    EXPECT_NE(host.notes()[0].find("libmarker.so: skipped, not named like a Pathlet plugin"), std::string::npos);
    EXPECT_TRUE(host.problems().empty()) << joined(host.problems());
    EXPECT_FALSE(constructor_ran()) << "the skipped library was opened";
}

TEST_F(LoadScratch, AWorldWritableFolderOrFileIsRefused) {
    put("marker_pass", "pathlet_marker.so");
    fs::permissions(dir / "plugins", fs::perms(0777));
    PassRegistry reg;
    PluginHost host(reg);
    host.load_dirs({(dir / "plugins").string()});
    ASSERT_EQ(host.problems().size(), 1u);
    EXPECT_NE(host.problems()[0].find("plugin folder is world-writable"), std::string::npos) << host.problems()[0];
    EXPECT_NE(host.problems()[0].find("nothing loaded from it"), std::string::npos) << host.problems()[0];
    EXPECT_EQ(reg.find("fixture_marker"), nullptr);
    // The folder fixed, the file itself world-writable.
    fs::permissions(dir / "plugins", fs::perms(0755));
    fs::permissions(dir / "plugins" / "pathlet_marker.so", fs::perms(0777));
    const std::string msg = load_error(host, (dir / "plugins" / "pathlet_marker.so").string());
    EXPECT_NE(msg.find("plugin file is world-writable"), std::string::npos) << msg;
    EXPECT_FALSE(constructor_ran());
}

TEST_F(LoadScratch, AFileOfAnotherUserIsRefused) {
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to give a file to another user (chown)";
    const fs::path p = put("marker_pass", "pathlet_marker.so");
    ASSERT_EQ(::chown(p.c_str(), 65534, 65534), 0);
    PassRegistry reg;
    PluginHost host(reg);
    const std::string msg = load_error(host, p.string());
    EXPECT_NE(msg.find("belongs to another user (uid 65534)"), std::string::npos) << msg;
    ASSERT_EQ(::chown((dir / "plugins").c_str(), 65534, 65534), 0);
    ASSERT_EQ(::chown(p.c_str(), 0, 0), 0);
    host.load_dirs({(dir / "plugins").string()});
    ASSERT_EQ(host.problems().size(), 1u);
    EXPECT_NE(host.problems()[0].find("plugin folder belongs to another user"), std::string::npos) << host.problems()[0];
    EXPECT_FALSE(constructor_ran());
}

TEST(PluginElf, ReadsEntryPointAndSdkFromTheSymbolTable) {
    std::ifstream in(fixture("good_pass"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const PluginSymbols s = read_plugin_symbols(bytes);
    EXPECT_TRUE(s.entry);
    EXPECT_EQ(s.sdk, PATHLET_SDK_FINGERPRINT);
    const PluginSymbols none = read_plugin_symbols_of_file(fixture("not_a_plugin"));
    EXPECT_FALSE(none.entry);
    EXPECT_EQ(none.sdk, "");
    // Cut anywhere, or with its section table pointing past the end: an ElfError, never a crash.
    for (size_t n : {size_t(0), size_t(3), size_t(63), size_t(64), bytes.size() / 2, bytes.size() - 1})
        EXPECT_THROW(read_plugin_symbols(std::string_view(bytes).substr(0, n)), ElfError) << n;
    std::string bad = bytes;
    bad[4] = 1;  // ELFCLASS32
    EXPECT_THROW(read_plugin_symbols(bad), ElfError);
}

TEST(PluginElf, FuzzRegressionsAreRefusedNotCrashes) {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(fs::path(PATHLET_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / "elf")) {
        std::ifstream in(e.path(), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        try {  // an ElfError, or symbols read past a bad entry (a name beyond the strings is skipped)
            const PluginSymbols s = read_plugin_symbols(bytes);
            EXPECT_EQ(s.sdk, "") << e.path();
        } catch (const ElfError&) {
        }
        ++n;
    }
    EXPECT_GE(n, 5u);
}

}  // namespace
