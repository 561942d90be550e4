// Every plugin-host failure gives a message naming the file and the reason, and leaves the
// registry as it was. The fixture plugins are built next to this test.
#include "plugin_host.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>
#include <fstream>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {

struct Nop : Pass {
    void execute(PassContext&) override {}
};

std::string fixture(const std::string& name) { return std::string(PATHLET_FIXTURE_DIR) + "/" + name + ".so"; }

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

}  // namespace

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
    expect_failure(p.string(), "cannot load");
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
