// GL limits (pathlet/gl_limits.hpp): units and binding points numbered by the engine within the
// context's limits, each kind in its own range; PATHLET_GL_LIMITS=minimum acts as a minimal GL 4.5
// driver, so what NVIDIA (8 image units) or any other driver at the minimum would refuse is
// refused here too, with the limit named; the reset between passes unbinds whatever was bound.
#include "engine_test_util.hpp"

#include <pathlet/gl_limits.hpp>
#include <pathlet/shader.hpp>

#include <cstdlib>

using namespace pathlet;
using namespace pathlet::testing_util;

namespace {

// PATHLET_GL_LIMITS=minimum for one scope.
struct MinimumLimits {
    MinimumLimits() { ::setenv("PATHLET_GL_LIMITS", "minimum", 1); }
    ~MinimumLimits() { ::unsetenv("PATHLET_GL_LIMITS"); }
};

void load_fixtures() {
    try {
        runtime().host.load_file(std::string(PATHLET_FIXTURE_DIR) + "/pathlet_limits_probe.so");
    } catch (const PluginError&) {
        // already loaded by an earlier test
    }
}

std::vector<std::string> shader_dirs() { return {test_file("shaders")}; }

std::string shader_error(const std::vector<std::string>& files) {
    try {
        ShaderProgram::from_files(files, shader_dirs());
    } catch (const ShaderError& e) {
        return e.what();
    }
    return "";
}

RenderOptions one_frame(const std::string& graph) {
    RenderOptions o;
    o.graph_path = test_file("graphs/" + graph);
    o.size = {2, 2};
    o.warmup = 0;
    o.write_images = false;
    o.quiet = true;
    return o;
}

}  // namespace

TEST(GlLimits, MinimumModeGivesTheSpecMinimumOfEveryCountAndKeepsSizes) {
    runtime();
    {
        MinimumLimits m;
        const GlLimits& L = gl_limits();
        EXPECT_TRUE(L.minimum_mode());
        EXPECT_EQ(L.get(GL_MAX_IMAGE_UNITS), 8);
        EXPECT_EQ(L.get(GL_MAX_FRAGMENT_IMAGE_UNIFORMS), 8);
        EXPECT_EQ(L.get(GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS), 0);
        EXPECT_EQ(L.get(GL_MAX_TEXTURE_IMAGE_UNITS), 16);
        EXPECT_EQ(L.get(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS), 8);
        EXPECT_EQ(L.get(GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES), 8);
        // Sizes stay the context's: a driver at those minimums could not hold the data at all.
        EXPECT_EQ(L.get(GL_MAX_TEXTURE_BUFFER_SIZE), L.context_value(GL_MAX_TEXTURE_BUFFER_SIZE));
        EXPECT_NE(L.source(GL_MAX_IMAGE_UNITS).find("PATHLET_GL_LIMITS=minimum"), std::string::npos);
    }
    const GlLimits& L = gl_limits();
    EXPECT_FALSE(L.minimum_mode());
    EXPECT_EQ(L.get(GL_MAX_IMAGE_UNITS), L.context_value(GL_MAX_IMAGE_UNITS));
    for (const GlLimit& l : gl_limit_table())  // every real driver meets the minimum
        EXPECT_GE(L.context_value(l.pname), l.minimum) << l.name;
}

TEST(GlLimits, AnUnknownModeIsAnErrorNamingTheVariable) {
    runtime();
    ::setenv("PATHLET_GL_LIMITS", "tiny", 1);
    std::string err;
    try {
        gl_limits();
    } catch (const std::exception& e) {
        err = e.what();
    }
    ::unsetenv("PATHLET_GL_LIMITS");
    EXPECT_NE(err.find("PATHLET_GL_LIMITS='tiny'"), std::string::npos) << err;
    EXPECT_NE(err.find("minimum"), std::string::npos) << err;
}

TEST(GlLimits, AStorageBlockInAGeometryShaderIsRefusedOnlyUnderTheMinimum) {
    runtime();
    const std::vector<std::string> files = {"limits_point.vert", "limits_geometry_storage.geom", "limits_point.frag"};
    EXPECT_EQ(shader_error(files), "");  // llvmpipe allows it
    MinimumLimits m;
    const std::string err = shader_error(files);
    EXPECT_NE(err.find("limits_geometry_storage.geom"), std::string::npos) << err;
    EXPECT_NE(err.find("geometry stage: 1"), std::string::npos) << err;
    EXPECT_NE(err.find("allows 0 (GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS"), std::string::npos) << err;
}

TEST(GlLimits, NineOutputResourcesAreRefusedUnderTheMinimumWithTheCount) {
    runtime();
    const std::vector<std::string> files = {"fullscreen.vert", "limits_outputs.frag"};
    std::vector<std::string> dirs = shader_dirs();
    dirs.push_back(source("shaders"));
    auto error = [&] {
        try {
            ShaderProgram::from_files(files, dirs);
        } catch (const ShaderError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error(), "");
    MinimumLimits m;
    const std::string err = error();
    EXPECT_NE(err.find("(4 + 3 + 2): 9"), std::string::npos) << err;
    EXPECT_NE(err.find("allows 8 (GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES"), std::string::npos) << err;
}

TEST(GlLimits, ImageUnitsAreNumberedApartFromSamplersAndTenFitWhereTheContextHasThem) {
    load_fixtures();
    if (gl_limits().get(GL_MAX_IMAGE_UNITS) < 10) GTEST_SKIP() << "this context has fewer than 10 image units";
    RenderOptions o = one_frame("limits_images.json");
    for (int k = 0; k < 10; ++k) o.keep.push_back("i" + std::to_string(k));
    std::vector<GLuint> got;
    render(runtime(), tiny_scene(), o, [&](const Executor& e, size_t) {
        for (int k = 0; k < 10; ++k) {
            GLuint v[4] = {};
            glGetTextureSubImage(e.texture("i" + std::to_string(k)).id, 0, 0, 0, 0, 1, 1, 1, GL_RED_INTEGER,
                                 GL_UNSIGNED_INT, sizeof v, v);
            got.push_back(v[0]);
        }
    });
    ASSERT_EQ(got.size(), 10u);
    for (GLuint k = 0; k < 10; ++k) EXPECT_EQ(got[k], k + 1) << "image pin i" << k;  // a shared unit mixes them up
}

TEST(GlLimits, APassNeedingMoreImageUnitsThanTheContextFailsInSetupNamingPassAndLimit) {
    load_fixtures();
    MinimumLimits m;
    std::string err;
    try {
        render(runtime(), tiny_scene(), one_frame("limits_images.json"));
    } catch (const std::exception& e) {
        err = e.what();
    }
    EXPECT_NE(err.find("limits_images.json:/passes/0"), std::string::npos) << err;
    EXPECT_NE(err.find("pass 'hog' (image_hog) failed in setup"), std::string::npos) << err;
    EXPECT_NE(err.find("'u_i8' needs image unit 8 (9 images"), std::string::npos) << err;
    EXPECT_NE(err.find("this context has 8 image units (GL_MAX_IMAGE_UNITS: the GL 4.5 minimum"), std::string::npos)
        << err;
}

TEST(GlLimits, BufferPinsGetBindingPointsAndTheResetUnbindsEveryUnitAPassUsed) {
    load_fixtures();
    RenderOptions o = one_frame("limits_storage.json");
    std::vector<float> px(4, -1.0f);
    RenderResult r = render(runtime(), tiny_scene(), o, [&](const Executor& e, size_t) {
        glGetTextureSubImage(e.texture("probe").id, 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, 16, px.data());
    });
    // The internal buffer reached the shader through DATA_BINDING.
    EXPECT_EQ(px, (std::vector<float>{0.125f, 0.25f, 0.5f, 1.0f}));
    // storage_probe used 20 texture units and a storage binding; the next pass starts with none.
    std::map<std::string, double> stats;
    for (const auto& p : r.profiler.passes())
        if (p.name == "after") stats = p.stats;
    ASSERT_EQ(stats.count("bound_texture_units"), 1u);
    EXPECT_EQ(stats["bound_texture_units"], 0.0);
    EXPECT_EQ(stats["bound_image_units"], 0.0);
    EXPECT_EQ(stats["bound_storage_bindings"], 0.0);
}
