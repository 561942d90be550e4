// Pass types for the graph tests, declared like real plugins declare them, without plugins.
#pragma once

#include "graph/graph_model.hpp"
#include "pass_registry.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pathlet::test {

// gbuffer, ssao, blur, lighting, taa, tonemap, mipgen, particles, counter, draw, anyout, mix
const PassRegistry& fake_registry();

GraphFile parse(const std::string& text);
// Parse + validate; a parse GraphError's diagnostics are returned too.
std::vector<Diagnostic> problems(const std::string& text);
CompiledGraph compile(const std::string& text, glm::ivec2 size = {1920, 1080});

// The diagnostic at `pointer` whose message contains `phrase`, or a failure listing all.
::testing::AssertionResult has_problem(const std::vector<Diagnostic>& d, const std::string& pointer,
                                       const std::string& phrase);
std::string all(const std::vector<Diagnostic>& d);

}  // namespace pathlet::test
