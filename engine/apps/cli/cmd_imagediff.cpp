// pathlet imagediff A B: how far two pictures of the same size are apart, in 8-bit levels, for
// comparing a GPU's frames with llvmpipe's (scripts/gpu-check.sh) or any two renders.
#include "args.hpp"
#include "commands.hpp"
#include "image_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pathlet::cli {
namespace {

int run(const std::vector<std::string>& argv) {
    Args a("imagediff", "Compares two images of the same size channel by channel in 8-bit levels (0..255; RGB, and\n"
                        "alpha where both have it) and prints, one 'NAME VALUE' a line: pixels, pixels_over (a channel\n"
                        "more than --threshold levels apart), share_over_pct, max_levels and rms_levels.\n"
                        "Exit status: 0 within --max-share (or without it), 1 beyond it or an unreadable file, 2 bad\n"
                        "usage.");
    std::string first, second, diff;
    int threshold = 8;
    double max_share = -1;
    a.positional("A", first, "an image (PNG, EXR, ...)")
        .positional("B", second, "the image to compare it with")
        .option("threshold", threshold, "LEVELS", "a pixel counts as different beyond this many 8-bit levels (8)")
        .option("max-share", max_share, "PCT", "exit 1 when more than PCT % of the pixels are different")
        .option("diff", diff, "OUT.png", "write the per-pixel largest difference (x 8, white = 32+ levels)")
        .example("pathlet imagediff gpu/variant1.png ref/variant1.png --max-share 0.5", "a GPU frame against llvmpipe's");
    if (!a.parse(argv)) return 0;
    if (threshold < 0 || threshold > 255) throw UsageError("--threshold must be 0..255");
    try {
        const Image x = read_image(first), y = read_image(second);
        if (x.width != y.width || x.height != y.height)
            throw std::runtime_error(first + " is " + std::to_string(x.width) + "x" + std::to_string(x.height) + " but " +
                                     second + " is " + std::to_string(y.width) + "x" + std::to_string(y.height));
        const std::vector<uint8_t> p = to_rgba8(x), q = to_rgba8(y);
        const bool alpha = x.channels == 4 && y.channels == 4;
        const size_t n = size_t(x.width) * size_t(x.height);
        size_t over = 0;
        int worst = 0;
        double sum = 0;
        Image d{x.width, x.height, 1, false, std::vector<float>(n)};
        for (size_t i = 0; i < n; ++i) {
            int m = 0;
            for (int c = 0; c < (alpha ? 4 : 3); ++c) {
                const int e = std::abs(int(p[4 * i + size_t(c)]) - int(q[4 * i + size_t(c)]));
                m = std::max(m, e);
                sum += double(e) * e;
            }
            over += m > threshold;
            worst = std::max(worst, m);
            d.pixels[i] = std::min(1.0f, float(m) / 32.0f);
        }
        const double share = n ? 100.0 * double(over) / double(n) : 0.0;
        std::printf("pixels %zu\npixels_over %zu\nshare_over_pct %.4f\nmax_levels %d\nrms_levels %.4f\n", n, over, share,
                    worst, n ? std::sqrt(sum / double(n * (alpha ? 4 : 3))) : 0.0);
        if (!diff.empty()) write_image(diff, d);
        return max_share >= 0 && share > max_share ? 1 : 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pathlet imagediff: error: %s\n", e.what());
        return 1;
    }
}

PATHLET_COMMAND("imagediff", "compare two images in 8-bit levels (share of pixels beyond a threshold)", run);

}  // namespace
}  // namespace pathlet::cli
