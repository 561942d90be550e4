// Golden-image comparison for GoogleTest: OIIO's compare in-process,
// mean/max error and failing-pixel count printed, actual/expected/diff images written on
// failure. A missing golden fails; PATHLET_UPDATE_GOLDENS=1 writes (or rewrites) goldens.
#pragma once

#include "image_io.hpp"
#include "image_probes.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pathlet {

// Passes when at most max_failing_fraction of the pixels differ by more than fail_threshold
// in some channel. An 8-bit golden is compared with `actual` rounded to 8 bits the way
// write_image rounds, so only real changes count.
::testing::AssertionResult matches_golden(const Image& actual, const std::string& golden_path,
                                          double fail_threshold = 2.0 / 255, double max_failing_fraction = 0.0005);

// Where failure images go: $PATHLET_GOLDEN_FAILURE_DIR, else golden_failures/ beside the
// test executable.
std::string golden_failure_dir();

}  // namespace pathlet
