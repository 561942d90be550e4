// overlay: what the study shows in every figure, drawn over the finished image: the animation
// time ("t = 4.50 s", top left; no unit where the data's time has none) and the speed legend
// (the colour bar with 3-5 round values on ticks and the data's velocity unit, beside the data:
// right of where its box projects, centred on it, inside the frame; for the direction colour
// map an x/y/z key at the right edge, for the bundle colour map the bundles' names beside their
// colours), sized from the output height so it is crisp and
// legible from 270 lines to 4K. Streamlines without time get neither clock nor
// speed. Text is rasterised with FreeType (text_raster.*); with show = false the image passes
// through bit for bit. Labels never cost the picture: a font that is missing or cannot be used
// gives one warning and the built-in font (builtin_font.cpp).
#include "text_raster.hpp"

#include <pathlet/gpu_scene.hpp>
#include <pathlet/lines.hpp>
#include <pathlet/plugin.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

// A text bitmap as a GL texture (R8, nearest: the quad is placed on whole pixels).
struct Label {
    GLuint tex = 0;
    int width = 0, height = 0, ascent = 0;
    int tex_w = 0, tex_h = 0;
    Label() = default;
    Label(const Label&) = delete;
    Label& operator=(const Label&) = delete;
    Label(Label&& o) noexcept
        : tex(std::exchange(o.tex, 0u)), width(o.width), height(o.height), ascent(o.ascent), tex_w(o.tex_w), tex_h(o.tex_h) {}
    ~Label() {
        if (tex) glDeleteTextures(1, &tex);
    }
    void set(const overlay::TextBitmap& b) {
        if (!tex || b.width > tex_w || b.height > tex_h) {  // grow only: the time label changes every frame
            if (tex) glDeleteTextures(1, &tex);
            tex_w = std::max(b.width, tex_w);
            tex_h = std::max(b.height, tex_h);
            glCreateTextures(GL_TEXTURE_2D, 1, &tex);
            glTextureStorage2D(tex, 1, GL_R8, tex_w, tex_h);
            glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
        std::vector<uint8_t> padded(size_t(tex_w) * size_t(tex_h), 0);
        for (int y = 0; y < b.height; ++y)
            std::copy_n(b.coverage.begin() + ptrdiff_t(y) * b.width, b.width, padded.begin() + ptrdiff_t(y) * tex_w);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(tex, 0, 0, 0, tex_w, tex_h, GL_RED, GL_UNSIGNED_BYTE, padded.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        width = b.width;
        height = b.height;
        ascent = b.ascent;
    }
};

// The text raster for `font`, or the built-in font with one warning per font file and process
// (setup runs again on every resize and parameter change).
std::unique_ptr<overlay::TextRaster> make_raster(const std::string& font, int px) {
    try {
        return std::make_unique<overlay::TextRaster>(font, px);
    } catch (const std::exception& e) {
        static std::set<std::string> warned;
        if (warned.insert(font).second)
            std::fprintf(stderr, "warning: overlay: %s; the labels use the built-in font (set overlay.font to a .ttf file)\n",
                         e.what());
        return std::make_unique<overlay::TextRaster>(px);
    }
}

// The legend's ticks: 3 to 5 round values ("nice numbers": 1, 2, 2.5 or 5 times a power of ten)
// inside [lo, hi], and the decimals their step needs.
struct Ticks {
    std::vector<double> values;
    int decimals = 0;
};
Ticks nice_ticks(double lo, double hi) {
    Ticks t;
    if (!(hi > lo)) return t;
    const double e0 = std::floor(std::log10((hi - lo) / 5.0));
    for (int e = int(e0) - 1; e <= int(e0) + 2 && t.values.empty(); ++e)
        for (double m : {1.0, 2.0, 2.5, 5.0}) {
            const double step = m * std::pow(10.0, e);
            const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
            const int n = int(last - first) + 1;
            if (n > 5) continue;
            if (n < 3) break;  // steps only grow from here: fewer ticks still
            for (double k = first; k <= last; k += 1.0) t.values.push_back(k * step);
            t.decimals = std::max(0, -int(std::floor(std::log10(step) + 1e-9)) + (m == 2.5 ? 1 : 0));
            break;
        }
    if (t.values.empty()) t.values = {lo, hi}, t.decimals = hi - lo >= 10 ? 0 : 2;  // no 3..5 split: the ends
    return t;
}
std::string format_tick(double v, int decimals) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::fabs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

// The text height at an output `lines` tall: 13 px at 270 lines, growing with the square root
// of the height (18 at 540, 26 at 1080, 37 at 2160): legible on a small figure, not shouting
// on a 4K frame.
int auto_font_px(float lines) { return std::clamp(int(std::lround(13.0f * std::sqrt(lines / 270.0f))), 12, 200); }

class Overlay : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        prog_ = &ctx.program({"overlay.vert", "overlay.frag"});
        if (!vao_) glCreateVertexArrays(1, &vao_);  // core profile: a draw needs a bound VAO
        const pathlet::Params& p = ctx.params();
        // --ssaa N: the overlay is laid out and rasterised for the output picture, each of its
        // pixels drawn as an N x N block, so the box filter gives back exactly the overlay of a
        // render without supersampling: it annotates the picture, it is not part of the scene the
        // supersampled render is a reference for (a glyph rasterised N times larger and filtered
        // down differs from the font's own small raster by a stroke's width).
        block_ = std::max(1, int(std::lround(ctx.pixel_scale())));
        const float lines = float(ctx.output_size().y / block_);
        font_px_ = int(std::lround(p.f("font_px") > 0.0f ? p.f("font_px") : float(auto_font_px(lines))));
        const std::string font = p.s("font").empty() ? overlay::default_font() : p.s("font");
        if (!raster_ || font != font_file_ || raster_->pixel_size() != font_px_) {
            raster_ = make_raster(font, font_px_);
            font_file_ = font;
        }
        const pathlet::GpuScene& scene = ctx.scene();
        float smin = p.f("speed_min") > 0.0f ? p.f("speed_min") : scene.speed_min();
        float smax = p.f("speed_max") > 0.0f ? p.f("speed_max") : scene.speed_max();
        if (!(smax > smin)) smax = smin + 1.0f;  // as the line kit does
        // Units as the data says them (or the user); none shown that nobody knows.
        const pathlet::Units& units = scene.cpu().lines.units;
        const std::string unit = p.s("speed_unit").empty() ? units.velocity : p.s("speed_unit");
        time_unit_ = units.time.empty() ? "" : " " + units.time;
        legend_min_ = smin;
        legend_max_ = smax;
        direction_ = p.s("colormap") == "direction";
        bundle_ = p.s("colormap") == "bundle";
        timeless_ = scene.cpu().lines.timeless;  // streamlines: no time, no speed to show
        const Ticks ticks = nice_ticks(smin, smax);
        ticks_.clear();
        tick_labels_.clear();
        tick_labels_.resize(ticks.values.size());
        for (size_t i = 0; i < ticks.values.size(); ++i) {
            ticks_.push_back(float(ticks.values[i]));
            tick_labels_[i].set(raster_->render(format_tick(ticks.values[i], ticks.decimals)));
        }
        unit_label_.set(raster_->render(direction_ ? "direction" : unit.empty() ? "speed" : "speed (" + unit + ")"));
        for (int k = 0; k < 3; ++k) axis_label_[k].set(raster_->render(std::string(1, char('x' + k))));
        bundle_labels_.clear();
        if (bundle_) {
            unit_label_.set(raster_->render("bundle"));
            std::vector<std::string> names = scene.cpu().lines.bundle_names;
            if (names.empty()) names = {"lines"};
            for (const std::string& n : names) bundle_labels_.emplace_back().set(raster_->render(n));
        }
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        pathlet::Texture src = ctx.texture("color"), dst = ctx.texture("final");
        glCopyImageSubData(src.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.width, dst.height, 1);
        if (!timeless_ && !direction_ && !bundle_) {  // the range the legend shows (or would): tests check it against the data
            ctx.stat("legend_min", double(legend_min_));
            ctx.stat("legend_max", double(legend_max_));
            ctx.stat("speed_min", double(legend_min_));  // the values in use where the parameters say auto
            ctx.stat("speed_max", double(legend_max_));
            ctx.stat("legend_ticks", double(ticks_.size()));  // what the bar is labelled with
            if (!ticks_.empty()) ctx.stat("legend_tick_first", double(ticks_.front()));
            if (ticks_.size() > 1) ctx.stat("legend_tick_step", double(ticks_[1] - ticks_[0]));
        }
        ctx.stat("font_px", double(font_px_));
        if (!p.b("show")) return;
        ctx.bind_framebuffer({"final"});
        glEnable(GL_BLEND);
        // Straight alpha over straight alpha: a transparent background gains the text's alpha.
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        prog_->use();
        glBindVertexArray(vao_);
        prog_->set("u_size", glm::vec2(ctx.output_size()));
        const glm::ivec2 size = ctx.output_size() / block_;  // the layout's pixels (see setup)
        const glm::vec4 ink(p.v3("text_color"), 1.0f);
        const float m = std::round(0.6f * float(font_px_));  // margin from the image border

        if (p.b("time") && !timeless_) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "t = %.2f%s", ctx.time(), time_unit_.c_str());
            time_label_.set(raster_->render(buf));
            text(time_label_, m, m, ink);
        }
        if (p.b("legend") && bundle_) {
            ctx.stat("legend_bundles", double(bundle_legend(size, m, ink)));
        } else if (p.b("legend") && direction_) {
            // Direction colours (RGB = |dx|, |dy|, |dz|): a swatch per axis under the title.
            const float sw = std::round(0.8f * float(font_px_)), gap = std::round(0.3f * float(font_px_));
            const float x1 = float(size.x) - m, x0 = x1 - sw;
            float y = std::round(0.5f * float(size.y) - 2.0f * sw);
            text(unit_label_, x1 - float(unit_label_.width), y - gap - float(unit_label_.height), ink);
            for (int k = 0; k < 3; ++k, y += std::round(1.4f * sw)) {
                glm::vec4 c(0.0f, 0.0f, 0.0f, 1.0f);
                c[k] = 1.0f;
                solid(x0 - 1, y - 1, x1 + 1, y + sw + 1, ink);
                solid(x0, y, x1, y + sw, c);
                text(axis_label_[k], x0 - gap - float(axis_label_[k].width), y + 0.5f * sw - 0.6f * float(axis_label_[k].ascent), ink);
            }
        } else if (p.b("legend") && !timeless_) {
            // A vertical bar beside the data (right of where its box projects, centred on it),
            // kept inside the frame: round values on ticks to its right, the unit above.
            const float f = float(font_px_);
            const float bar_w = std::round(0.6f * f), tick = std::round(0.3f * f), gap = std::round(0.3f * f);
            const float bar_h = std::round(std::max(0.32f * float(size.y), 6.0f * f));
            float labels_w = 0.0f;
            for (const Label& l : tick_labels_) labels_w = std::max(labels_w, float(l.width));
            const float block_w = bar_w + tick + gap + labels_w;  // the title may reach further left
            const glm::vec4 data = data_rect(ctx) / float(block_);  // x0, y0, x1, y1 from the top left
            const float x0 = std::round(std::clamp(data.z + 1.5f * f, m, float(size.x) - m - block_w));
            const float x1 = x0 + bar_w;
            const float top = m + float(unit_label_.height) + gap;  // room for the title
            const float y0 = std::round(std::clamp(0.5f * (data.y + data.w) - 0.5f * bar_h, top,
                                                   std::max(top, float(size.y) - m - bar_h)));
            const float y1 = y0 + bar_h;
            solid(x0 - 1, y0 - 1, x1 + 1, y1 + 1, ink);  // a 1 px frame
            prog_->set("u_mode", 1);
            rect(x0, y0, x1, y1);
            for (size_t i = 0; i < ticks_.size(); ++i) {
                const float y = std::round(y1 - (ticks_[i] - legend_min_) / (legend_max_ - legend_min_) * bar_h);
                // On whole pixels (an odd thickness would end half-way through a row, which the
                // rasteriser gives to one row, a supersampled render to two).
                const float thick = std::max(1.0f, std::round(f / 14.0f)), y_top = std::floor(y - 0.5f * thick + 0.5f);
                solid(x1, y_top, x1 + tick, y_top + thick, ink);
                const Label& l = tick_labels_[i];
                text(l, x1 + tick + gap, y - 0.5f * float(l.ascent), ink);
            }
            text(unit_label_, std::max(m, std::min(x0, float(size.x) - m - float(unit_label_.width))),
                 y0 - gap - float(unit_label_.height), ink);
        }
    }

    ~Overlay() override {
        if (vao_) glDeleteVertexArrays(1, &vao_);
    }

private:
    // Where the data can be this frame, in pixels from the top left: the projection of the
    // cylinder about the camera's up axis (through the box's centre) that holds the box. It
    // hugs a vessel seen side on and stays put while an orbit turns the data about that axis,
    // so the legend beside it does not slide. The middle of the frame where it reaches behind
    // the camera.
    static glm::vec4 data_rect(const pathlet::PassContext& ctx) {
        const glm::vec2 size(ctx.output_size());
        const glm::vec4 middle(0.5f * size.x, 0.5f * size.y, 0.5f * size.x, 0.5f * size.y);
        const pathlet::Bounds b = ctx.scene().bounds();
        const pathlet::Camera& cam = ctx.camera();
        if (!b.valid() || !(glm::length(cam.up) > 0.0f)) return middle;
        const glm::vec3 up = glm::normalize(cam.up), center = b.center();
        float radius = 0.0f, h0 = 1e30f, h1 = -1e30f;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 q = glm::vec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z) - center;
            const float h = glm::dot(q, up);
            radius = std::max(radius, glm::length(q - h * up));
            h0 = std::min(h0, h), h1 = std::max(h1, h);
        }
        const glm::vec3 a = std::fabs(up.x) < 0.9f ? glm::normalize(glm::cross(up, glm::vec3(1, 0, 0)))
                                                   : glm::normalize(glm::cross(up, glm::vec3(0, 1, 0)));
        const glm::vec3 a2 = glm::cross(up, a);
        const glm::mat4 clip = cam.proj * cam.view;
        glm::vec2 mn(1e30f), mx(-1e30f);
        for (int k = 0; k < 48; ++k) {  // the two rims, every 7.5 degrees
            const float t = float(k % 24) * (2.0f * 3.14159265f / 24.0f);
            const glm::vec3 p = center + radius * (std::cos(t) * a + std::sin(t) * a2) + (k < 24 ? h0 : h1) * up;
            const glm::vec4 c = clip * glm::vec4(p, 1.0f);
            if (!(c.w > 1e-6f)) return middle;
            const glm::vec2 px((c.x / c.w * 0.5f + 0.5f) * size.x, (0.5f - c.y / c.w * 0.5f) * size.y);
            mn = glm::min(mn, px);
            mx = glm::max(mx, px);
        }
        return {mn, mx};
    }
    // The bundles' names, each left of a swatch of its colour (colormap_bundle in the shader), in
    // bundle order down the right edge under the title; as many as fit, then "+N more".
    // Returns the swatches drawn.
    size_t bundle_legend(glm::ivec2 size, float m, glm::vec4 ink) {
        const float sw = std::round(0.8f * float(font_px_)), gap = std::round(0.3f * float(font_px_));
        // A row fits a name's descenders and underscores, not only the swatch.
        const float row = std::round(std::max(1.4f * sw, 1.3f * float(font_px_))), x1 = float(size.x) - m, x0 = x1 - sw;
        const float top = m + float(unit_label_.height) + gap;
        const size_t fit = size_t(std::max(1.0f, std::floor((float(size.y) - m - top) / row)));
        const size_t n = bundle_labels_.size();
        const size_t shown = n <= fit ? n : fit - 1;
        float y = std::round(std::max(top, 0.5f * float(size.y) - 0.5f * float(n <= fit ? n : fit) * row));
        text(unit_label_, x1 - float(unit_label_.width), y - gap - float(unit_label_.height), ink);
        for (size_t k = 0; k < shown; ++k, y += row) {
            solid(x0 - 1, y - 1, x1 + 1, y + sw + 1, ink);
            prog_->set("u_mode", 3);
            prog_->set("u_bundle", int(k));
            rect(x0, y, x1, y + sw);
            const Label& l = bundle_labels_[k];
            text(l, x0 - gap - float(l.width), y + 0.5f * sw - 0.6f * float(l.ascent), ink);
        }
        if (shown < n) {
            more_label_.set(raster_->render("+" + std::to_string(n - shown) + " more"));
            text(more_label_, x1 - float(more_label_.width), y + 0.5f * sw - 0.6f * float(more_label_.ascent), ink);
        }
        return shown;
    }
    void rect(float x0, float y0, float x1, float y1) {
        prog_->set("u_rect", glm::vec4(x0, y0, x1, y1) * float(block_));
        glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    }
    void solid(float x0, float y0, float x1, float y1, glm::vec4 c) {
        prog_->set("u_mode", 2);
        prog_->set("u_color", c);
        rect(x0, y0, x1, y1);
    }
    void text(const Label& l, float x, float y, glm::vec4 c) {
        x = std::round(x);
        y = std::round(y);
        prog_->set("u_mode", 0);
        prog_->set("u_color", c);
        prog_->bind_texture("u_text", l.tex);
        // The quad spans the whole (grown) texture; the unused part is zero coverage.
        rect(x, y, x + float(l.tex_w), y + float(l.tex_h));
    }

    pathlet::ShaderProgram* prog_ = nullptr;
    GLuint vao_ = 0;
    std::unique_ptr<overlay::TextRaster> raster_;
    std::string font_file_;
    int font_px_ = 0;
    int block_ = 1;  // output pixels per layout pixel: the --ssaa factor
    Label time_label_, unit_label_, axis_label_[3];
    std::vector<Label> tick_labels_;  // grows only on setup; Label owns its texture
    std::vector<Label> bundle_labels_;  // the bundles' names, in bundle order
    Label more_label_;
    std::vector<float> ticks_;
    std::string time_unit_;
    float legend_min_ = 0, legend_max_ = 0;
    bool direction_ = false, bundle_ = false, timeless_ = false;
};

}  // namespace

PATHLET_PLUGIN("overlay", {
    sink->add(pathlet::PassTypeBuilder("overlay",
                                       "the animation time and the speed legend (colour bar, range, unit) over the "
                                       "finished image, as in the study's figures")
                  .param_bool("show", true, "draw the overlay (false: the image passes through unchanged)")
                  .param_bool("time", true, "the time label \"t = 4.50 s\", top left")
                  .param_bool("legend", true, "the speed colour bar with 3-5 round values and the unit, beside the data")
                  .param_enum("colormap", "green_red", pathlet::lines::colormaps(),
                              "the line pass's colour map (tie both to one graph variable); direction shows an x/y/z key, "
                              "bundle the bundles' names beside their colours")
                  .param_float("speed_min", 0.0, -1.0, 1e9,
                               "speed at the bar's bottom, as the line pass's; <= 0: the data's 1st percentile",
                               {.at_most = "speed_max", .automatic_at_or_below = 0.0})
                  .param_float("speed_max", 0.0, -1.0, 1e9,
                               "speed at the bar's top, as the line pass's; <= 0: the data's 99th percentile")
                  .param_string("speed_unit", "",
                                "unit shown with the legend; empty = the data's velocity unit where its file says it "
                                "(else the legend just says \"speed\")")
                  .param_float("font_px", 0.0, 0.0, 400.0,
                               "text height in pixels; 0 = auto: 13 px at 270 lines, growing with the square root of the "
                               "output height (18 at 540, 26 at 1080, 37 at 2160)")
                  .param_string("font", "", "a TrueType/OpenType font file (.ttf, .otf, .ttc; nothing else is opened); empty = "
                                            "DejaVu Sans (share/pathlet/fonts, else fonts-dejavu-core); one that cannot be "
                                            "used gives a warning and the built-in font")
                  .param_color("text_color", {0.12f, 0.12f, 0.12f}, "colour of the text and the bar's frame")
                  .input_texture("color", "rgba8", "the finished image (its legend must be the lines': colormap, "
                                 "speed_min and speed_max as the nearest line pass before it has them)",
                                 {.same_params = {"colormap", "speed_min", "speed_max"}})
                  .output_texture("final", "rgba8", "the image with time and legend")
                  .make<Overlay>());
})
