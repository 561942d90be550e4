// A profile recorded against a fake clock, so every statistic is known in advance.
#pragma once

#include "profiler/profiler.hpp"

namespace pathlet {

// Frame k: pass "shadow" lasts (warm-up ? 100 : 1 + k) ms, "lines" 2 ms, 0.5 ms between.
struct FakeRun {
    double t = 0;
    Profiler p;
    explicit FakeRun(int frames, int warmup = 2) {
        p.set_clock([this] { return t; });
        p.set_warmup_frames(warmup);
        p.init(TimingBackend::CpuFinish, "llvmpipe");
        for (int k = 0; k < frames; ++k) {
            p.begin_frame(uint64_t(k));
            p.begin_pass("shadow");
            t += k < warmup ? 100 : 1 + k;
            p.end_pass();
            t += 0.5;
            p.begin_pass("lines");
            p.add_stat("lines", "segments", k < warmup ? 1e9 : 1000 + k);
            t += 2;
            p.end_pass();
            p.end_frame();
            t += 10;  // between frames: not part of any frame
        }
    }
};

}  // namespace pathlet
