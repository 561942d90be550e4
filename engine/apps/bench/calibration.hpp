// The machine's own speed, timed beside a bench's runs: a fixed GL workload (a fragment
// shader of fixed cost: short draws each waited for, as a frame's passes are, then a long one
// over a fixed 256x256 target, glFinish-bracketed), the same on every
// run and every version of Pathlet. On llvmpipe it runs on the same threads and cores as the
// frames, so other load on the machine slows it as it slows them; on a GPU it follows the
// clock. results.json records its samples per run (before and after each, interleaved with
// the runs) and `bench --compare` divides the times by the ratio of the two machines' speeds.
#pragma once

#include <pathlet/gl.hpp>

#include <string>
#include <vector>

namespace pathlet::cli::bench {

class Calibration {
public:
    Calibration();  // needs a current GL 4.5 context; compiles the shader
    ~Calibration();
    Calibration(const Calibration&) = delete;
    Calibration& operator=(const Calibration&) = delete;

    double sample_ms();  // one timing of the workload, in wall-clock ms
    std::vector<double> samples_ms(int n);

    static const char* description();  // what the workload is, recorded with its samples

private:
    GLuint prog_ = 0, vao_ = 0, fbo_ = 0, tex_ = 0;
};

double median_of(std::vector<double> v);  // 0 for none

}  // namespace pathlet::cli::bench
