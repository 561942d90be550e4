// quality --reference in the process (measure_against_reference): a reference whose frames
// lost fragments is refused, naming them; the tested graph's incomplete frames are named in the
// result; nothing to measure is n/a (NaN), never a perfect score.
#include "cycle_list.hpp"
#include "frame_capture.hpp"
#include "reference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace pathlet;

namespace {

quality::ReferenceOptions options(const std::string& graph, const std::string& reference) {
    quality::ReferenceOptions o;
    o.graph_path = graph;
    o.reference_path = reference;
    o.size = {160, 90};
    o.time = TimeRange{2.0, 2.08, 0.04};
    o.sets = {"overlay=false"};
    return o;
}

std::string shipped(const std::string& name) { return std::string(PATHLET_SOURCE_DIR) + "/graphs/" + name + ".json"; }

}  // namespace

// The list holding node 0 made cyclic in frame 1 of 3: its walk is cut, so frame 1 of that graph
// is not exact. As the reference it is refused; as the tested graph its frame is named.
TEST(ReferenceFrames, AReferenceWithACutWalkIsRefusedAndATestedGraphsIsNamed) {
    add_cycle_list_pass(test_runtime());
    const std::string cyclic = write_cyclic_list_graph(test_scratch_dir("pathlet_refframes") + "/cyclic.json", 1);
    try {
        quality::measure_against_reference(test_runtime(), small_phantom_scene(), options(shipped("variant2_wboit"), cyclic));
        ADD_FAILURE() << "a reference with a cut walk was measured against";
    } catch (const std::runtime_error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("the reference cyclic_list rendered incomplete frames (1 of 3)"), std::string::npos) << m;
    }
    const quality::ReferenceResult r =
        quality::measure_against_reference(test_runtime(), small_phantom_scene(), options(cyclic, shipped("variant2_exact")));
    EXPECT_EQ(r.incomplete_frames, (std::vector<size_t>{1}));
    EXPECT_NE(quality::incomplete_frames_note(r).find("cyclic_list rendered incomplete frames (1 of 3)"), std::string::npos)
        << quality::incomplete_frames_note(r);
    EXPECT_EQ(r.frames, 3u);
    EXPECT_EQ(r.per_frame.size(), 3u) << "every frame measured as it came";
}

TEST(ReferenceFrames, NothingToMeasureIsNaNNotAPerfectScore) {
    quality::ReferenceOptions o = options(shipped("variant2_wboit"), shipped("variant2_exact"));
    o.size = {8, 8};
    const quality::ReferenceResult r = quality::measure_against_reference(test_runtime(), small_phantom_scene(), o);
    EXPECT_FALSE(r.metrics.ssim_measured());
    EXPECT_TRUE(std::isnan(r.metrics.ssim));
}
