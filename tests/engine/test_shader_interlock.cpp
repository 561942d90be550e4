// A fragment stage that uses the fragment shader interlock is linked as one object (shader.cpp,
// merge_interlocked_fragments): NVIDIA 580 drops the interlock from a stage of several objects
// and fails at link. What the driver gets is read back through PATHLET_SHADER_DUMP, so the test
// runs where the extension is missing too (llvmpipe refuses the compile; NVIDIA links it).
#include "engine_test_util.hpp"

#include <pathlet/shader.hpp>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <fstream>
#include <sstream>
#include <unistd.h>

using namespace pathlet;
using namespace pathlet::testing_util;
namespace fs = std::filesystem;

namespace {

struct Dir {
    fs::path path = fs::temp_directory_path() / ("pathlet_interlock_" + std::to_string(::getpid()));
    Dir() { fs::remove_all(path), fs::create_directories(path / "src"); }
    ~Dir() { fs::remove_all(path); }
    void write(const std::string& name, const std::string& text) const { std::ofstream(path / "src" / name) << text; }
};

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// Compiles the program with PATHLET_SHADER_DUMP set; returns the dumped files (name -> text).
std::map<std::string, std::string> dumped(const Dir& d, const std::vector<std::string>& files, std::string* error) {
    const fs::path dump = d.path / ("dump" + std::to_string(std::rand()));
    ::setenv("PATHLET_SHADER_DUMP", dump.c_str(), 1);
    try {
        ShaderProgram::from_files(files, {(d.path / "src").string()}, {"PROBE_DEFINE 1"});
    } catch (const ShaderError& e) {
        *error = e.what();
    }
    ::unsetenv("PATHLET_SHADER_DUMP");
    std::map<std::string, std::string> out;
    for (const auto& f : fs::directory_iterator(dump)) out[f.path().filename().string().substr(7)] = read(f.path());
    return out;
}

const char* kVert = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
const char* kHook = "#version 450 core\nvec4 hook_color(vec4 c) { return c * 0.5; }  // HOOK_BODY\n";
std::string main_frag(bool interlock) {
    return std::string("#version 450 core\n") +
           (interlock ? "#extension GL_ARB_fragment_shader_interlock : require\nlayout(pixel_interlock_ordered) in;\n" : "") +
           "vec4 hook_color(vec4 c);\nlayout(std430, binding = 0) coherent buffer B { uint n[]; };\nout vec4 o;\n"
           "void main() {\n" +
           (interlock ? "    beginInvocationInterlockARB();\n" : "") + "    n[0] += 1u;\n" +
           (interlock ? "    endInvocationInterlockARB();\n" : "") + "    o = hook_color(vec4(1.0));\n}\n";
}

}  // namespace

TEST(ShaderInterlock, AnInterlockedFragmentStageIsOneObjectWithItsHookAppended) {
    runtime();
    Dir d;
    d.write("probe.vert", kVert);
    d.write("hook.frag", kHook);
    d.write("locked.frag", main_frag(true));
    std::string error;
    const auto files = dumped(d, {"probe.vert", "locked.frag", "hook.frag"}, &error);
    ASSERT_EQ(files.size(), 2u) << "expected the vertex stage and one fragment object";
    ASSERT_TRUE(files.count("locked.frag+hook.frag")) << "the fragment object is the one that declares the interlock";
    const std::string& frag = files.at("locked.frag+hook.frag");
    EXPECT_EQ(count(frag, "HOOK_BODY"), 1u) << frag;                    // the hook, appended once
    EXPECT_LT(frag.find("beginInvocationInterlockARB"), frag.find("HOOK_BODY")) << frag;  // after the shader
    EXPECT_EQ(count(frag, "#version"), 1u) << frag;                     // its own version line dropped
    EXPECT_EQ(count(frag, "#define PROBE_DEFINE"), 1u) << frag;         // the defines not repeated
    // Where the driver lacks the extension (llvmpipe) the compile fails, naming the merged object.
    if (!error.empty()) {
        EXPECT_NE(error.find("locked.frag"), std::string::npos) << error;
    }
}

TEST(ShaderInterlock, WithoutAnInterlockTheHookStaysItsOwnObject) {
    runtime();
    Dir d;
    d.write("probe.vert", kVert);
    d.write("hook.frag", kHook);
    d.write("free.frag", main_frag(false));
    std::string error;
    const auto files = dumped(d, {"probe.vert", "free.frag", "hook.frag"}, &error);
    EXPECT_EQ(error, "");  // links on every driver
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(count(files.at("free.frag"), "HOOK_BODY"), 0u);
    EXPECT_EQ(count(files.at("hook.frag"), "HOOK_BODY"), 1u);
}
