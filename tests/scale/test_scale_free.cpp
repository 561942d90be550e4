// Scale-free defaults: every shipped graph draws the same picture of the same data whether its
// coordinates are in metres, millimetres or micrometres. The small phantom (lines and wall)
// is rendered at 1x, 0.01x and 100x (positions, velocities and the wall multiplied; times
// kept) at the default framing, and every 8-bit output must match the 1x one within a small
// RMS. A width, halo depth, AO reach, level of detail, fade length or camera distance in world
// units would change the picture with the scale. The legend's numbers are speeds, which do
// scale: it is switched off (the time label stays).
#include "frame_capture.hpp"
#include "image_probes.hpp"
#include "shipped_graphs.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>

using namespace pathlet;

namespace {

Scene scaled(const Scene& s, float k) {
    Scene out = s;
    for (auto& p : out.lines.position) p *= k;
    for (auto& v : out.lines.velocity) v *= k;
    if (out.mesh)
        for (auto& p : out.mesh->position) p *= k;
    return out;
}

// RMS over every channel of every pixel, in 8-bit levels.
double rms_levels(const Image& a, const Image& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
        const double d = 255.0 * (double(a.pixels[i]) - double(b.pixels[i]));
        sum += d * d;
    }
    return std::sqrt(sum / double(std::max<size_t>(a.pixels.size(), 1)));
}

// One graph; the test below runs every shipped graph in one process (GL and the phantom are
// set up once: a process per graph cost ~9 s each on the 2-core CI machine).
void expect_scale_free(const ShippedGraph& g) {
    SCOPED_TRACE(g.name);
    test_runtime();  // the GL context unsupported_here asks
    if (const std::string why = g.unsupported_here(); !why.empty()) {
        std::printf("skipped: %s\n", why.c_str());
        return;
    }
    RenderOptions opt;
    opt.graph_path = g.path;
    opt.size = {320, 180};
    opt.time.start = 2.0;  // the middle of the small phantom's 0..4 s
    if (g.has_pass("overlay")) opt.sets.push_back("overlay.legend=false");
    std::vector<std::string> outputs;  // what a person sees: the 8-bit outputs
    for (const auto& o : g.file.outputs)
        for (const auto& r : g.file.resources)
            if (r.name == o.resource && r.format == "rgba8") outputs.push_back(o.resource);
    ASSERT_FALSE(outputs.empty()) << g.name << " has no rgba8 output";

    const Frame base = render_frame(test_runtime(), small_phantom_scene(), opt, outputs);
    for (const std::string& name : outputs) {
        const Image& ref = base[name];
        ASSERT_FALSE(has_nan(ref));
        // The reference must show the data, or the comparison proves nothing: a share of the
        // pixels away from the white background.
        size_t drawn = 0;
        for (size_t i = 0; i + 2 < ref.pixels.size(); i += size_t(ref.channels))
            drawn += ref.pixels[i] + ref.pixels[i + 1] + ref.pixels[i + 2] < 2.9f;
        if (g.draws_lines) { EXPECT_GT(double(drawn), 0.01 * ref.width * ref.height) << name << " shows no data"; }
    }
    for (float k : {0.01f, 100.0f}) {
        const Frame f = render_frame(test_runtime(), scaled(small_phantom_scene(), k), opt, outputs);
        for (const std::string& name : outputs) {
            const double rms = rms_levels(f[name], base[name]);
            EXPECT_LT(rms, 0.5) << g.name << " '" << name << "' at " << k << "x the scale: RMS " << rms << " levels";
            ::testing::Test::RecordProperty(g.name + "_" + name + "_rms_x" + (k < 1 ? "0.01" : "100"), std::to_string(rms));
        }
    }
}

TEST(ScaleFree, EveryShippedGraphDrawsTheSamePictureAtAHundredthAndAHundredTimesTheScale) {
    for (const ShippedGraph& g : shipped_graphs()) expect_scale_free(g);
}

}  // namespace
