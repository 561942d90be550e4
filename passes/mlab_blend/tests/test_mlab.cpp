// MLAB with depth buckets (mlab_bucket -> mlab_blend). Where the driver lacks
// GL_ARB_fragment_shader_interlock (llvmpipe), the graph must fail at setup with one line naming
// the extension, the driver and the techniques that need none, and `pathlet render` must exit
// with 1 having written nothing. Where the driver has it, the picture must be near the exact
// resolve of the same fragments.
#include "frame_capture.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

using namespace pathlet;
namespace fs = std::filesystem;

namespace {

const std::string kSrc = PATHLET_SOURCE_DIR;

bool has_interlock() {
    test_runtime();  // the GL context
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))),
                        "GL_ARB_fragment_shader_interlock") == 0)
            return true;
    return false;
}

RenderOptions small(const std::string& graph) {
    RenderOptions opt;
    opt.graph_path = kSrc + "/graphs/" + graph + ".json";
    opt.sets = {"line_width=1.2", "window=3", "overlay=false"};
    opt.size = {160, 120};
    opt.time.start = 6.0;
    return opt;
}

}  // namespace

TEST(Mlab, WithoutInterlockTheGraphFailsAtSetupWithOneLine) {
    if (has_interlock()) GTEST_SKIP() << "this driver has GL_ARB_fragment_shader_interlock: the next test renders";
    for (const char* graph : {"variant2_mlabdb", "variant2_mlabdb_ao"}) {
        std::string msg;
        try {
            render_frame(test_runtime(), helix_bundle_scene(), small(graph), {"final"});
        } catch (const std::exception& e) {
            msg = e.what();
        }
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
        for (const char* part : {"needs GL_ARB_fragment_shader_interlock", "which this driver (llvmpipe) lacks",
                                 "variant2_exact, variant2_mboit and variant2_wboit need none", "/passes/",
                                 "failed in setup"})
            EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' in: " << msg;
        EXPECT_NE(msg.find(std::string(graph) + ".json"), std::string::npos) << "names the graph: " << msg;
    }
    // The command: exit status 1, the line on stderr, no frame written.
    const fs::path out = fs::temp_directory_path() / ("pathlet_mlab_" + std::to_string(::getpid()));
    const std::string err_file = out.string() + ".err";
    const std::string cmd = std::string(PATHLET_CLI) + " render variant2_mlabdb --data " + kSrc +
                            "/tests/engine/data/two_lines.vtk --time 1 --size 64x48 --out " +
                            out.string() + " >/dev/null 2>" + err_file;
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    std::string err;
    if (FILE* f = std::fopen(err_file.c_str(), "r")) {
        char buf[4096];
        size_t n;
        while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) err.append(buf, n);
        std::fclose(f);
    }
    size_t lines_with_it = 0, at = 0;
    while ((at = err.find("needs GL_ARB_fragment_shader_interlock", at)) != std::string::npos) ++lines_with_it, ++at;
    EXPECT_EQ(lines_with_it, 1u) << err;
    EXPECT_FALSE(fs::exists(out / "variant2_mlabdb" / "00000.png")) << "nothing written";
    fs::remove_all(out);
    fs::remove(err_file);
}

TEST(Mlab, WithInterlockNearTheExactResolve) {
    if (!has_interlock()) GTEST_SKIP() << "this driver lacks GL_ARB_fragment_shader_interlock (the test above)";
    Frame m = render_frame(test_runtime(), helix_bundle_scene(), small("variant2_mlabdb"), {"final"});
    Frame e = render_frame(test_runtime(), helix_bundle_scene(), small("variant2_oit"), {"oit_color"});
    double sum = 0.0;
    size_t n = 0;
    for (int y = 0; y < m["final"].height; ++y)
        for (int x = 0; x < m["final"].width; ++x) {
            if (e["oit_color"].at(x, y, 3) < 1.0f) continue;
            for (int k = 0; k < 3; ++k) sum += std::abs(double(m["final"].at(x, y, k)) - e["oit_color"].at(x, y, k));
            ++n;
        }
    ASSERT_GT(n, 500u);
    EXPECT_LT(sum / (3.0 * n), 6.0 / 255) << "mean difference from the sorted lists";
}
