// x^n for a whole exponent n fixed when the program is built (a #define from the pass's C++ side,
// pathlet::whole_exponent in pathlet/shader.hpp): square-and-multiply, which the compiler unrolls
// into ~2 log2(n) products. pow() is exp2(n log2 x), two polynomial approximations per call on
// llvmpipe, where a G-buffer or LineAO fragment pays it dozens of times per pixel. x >= 0.
#ifndef PATHLET_POW_WHOLE_GLSL
#define PATHLET_POW_WHOLE_GLSL

float pow_whole(float x, const int n) {
    float r = 1.0;
    for (int bit = 0; bit < 11; ++bit) {  // n < 2048
        if ((n & (1 << bit)) != 0) r *= x;
        x *= x;
    }
    return r;
}

#endif
