// Long CPU work (tracing, phantom generation) reports a fraction and a stage name; this
// shows it with the engine's progress bar (a \r line on a terminal, plain lines otherwise).
#pragma once

#include "common/progress.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <string>
#include <string_view>

namespace pathlet {

class FractionProgress {
public:
    explicit FractionProgress(const std::string& what, bool quiet = false) : bar_(what, kSteps, quiet, /*counts=*/false) {}
    std::function<void(double, std::string_view)> callback() {
        return [this](double f, std::string_view stage) {
            bar_.update(size_t(std::clamp(f, 0.0, 1.0) * kSteps), std::string(stage));
        };
    }
    void finish(const std::string& summary) { bar_.finish(summary); }
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    static constexpr size_t kSteps = 1000;
    Progress bar_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace pathlet
