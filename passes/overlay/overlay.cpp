// overlay: what the study shows in every figure, drawn over the finished image: the animation
// time ("t = 4.50 s", top left; no unit where the data's time has none) and the speed legend
// (the colour bar with its range and the data's velocity unit, right edge, vertically
// centred; for the direction colour map an x/y/z key), sized from the output height so it is
// crisp and equally large at any resolution. Streamlines without time get neither clock nor
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

namespace {

// A text bitmap as a GL texture (R8, nearest: the quad is placed on whole pixels).
struct Label {
    GLuint tex = 0;
    int width = 0, height = 0, ascent = 0;
    int tex_w = 0, tex_h = 0;
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

// Legend numbers with as many decimals as their size needs (1250, 12.5, 0.35).
std::string format_speed(float v) {
    char buf[32];
    const float a = std::fabs(v);
    std::snprintf(buf, sizeof buf, a >= 100.0f ? "%.0f" : a >= 10.0f ? "%.1f" : "%.2f", double(v));
    return buf;
}

class Overlay : public pathlet::Pass {
public:
    void setup(pathlet::PassContext& ctx) override {
        prog_ = &ctx.program({"overlay.vert", "overlay.frag"});
        if (!vao_) glCreateVertexArrays(1, &vao_);  // core profile: a draw needs a bound VAO
        const pathlet::Params& p = ctx.params();
        const int h = ctx.output_size().y;
        font_px_ = p.f("font_px") > 0.0f ? int(std::lround(p.f("font_px") * ctx.pixel_scale()))
                                          : std::clamp(int(std::lround(float(h) / 28.0f)), 10, 400);
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
        timeless_ = scene.cpu().lines.timeless;  // streamlines: no time, no speed to show
        max_label_.set(raster_->render(format_speed(smax)));
        min_label_.set(raster_->render(format_speed(smin)));
        unit_label_.set(raster_->render(direction_ ? "direction" : unit.empty() ? "speed" : "speed (" + unit + ")"));
        for (int k = 0; k < 3; ++k) axis_label_[k].set(raster_->render(std::string(1, char('x' + k))));
    }

    void execute(pathlet::PassContext& ctx) override {
        const pathlet::Params& p = ctx.params();
        pathlet::Texture src = ctx.texture("color"), dst = ctx.texture("final");
        glCopyImageSubData(src.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.id, GL_TEXTURE_2D, 0, 0, 0, 0, dst.width, dst.height, 1);
        if (!timeless_ && !direction_) {  // the range the legend shows (or would): tests check it against the data
            ctx.stat("legend_min", double(legend_min_));
            ctx.stat("legend_max", double(legend_max_));
        }
        if (!p.b("show")) return;
        ctx.bind_framebuffer({"final"});
        glEnable(GL_BLEND);
        // Straight alpha over straight alpha: a transparent background gains the text's alpha.
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        prog_->use();
        glBindVertexArray(vao_);
        const glm::ivec2 size = ctx.output_size();
        prog_->set("u_size", glm::vec2(size));
        const glm::vec4 ink(p.v3("text_color"), 1.0f);
        const float m = std::round(0.6f * float(font_px_));  // margin from the image border

        if (p.b("time") && !timeless_) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "t = %.2f%s", ctx.time(), time_unit_.c_str());
            time_label_.set(raster_->render(buf));
            text(time_label_, m, m, ink);
        }
        if (p.b("legend") && direction_) {
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
            // A vertical bar at the right edge, centred: the data sits in the middle at the
            // default framing. Numbers to its left, right-aligned; the unit above.
            const float bar_w = std::round(0.55f * float(font_px_));
            const float bar_h = std::round(std::max(0.28f * float(size.y), 4.0f * float(font_px_)));
            const float x1 = float(size.x) - m, x0 = x1 - bar_w;
            const float y0 = std::round(0.5f * (float(size.y) - bar_h)), y1 = y0 + bar_h;
            solid(x0 - 1, y0 - 1, x1 + 1, y1 + 1, ink);  // a 1 px frame
            prog_->set("u_mode", 1);
            rect(x0, y0, x1, y1);
            const float gap = std::round(0.3f * float(font_px_));
            text(max_label_, x0 - gap - float(max_label_.width), y0 - float(max_label_.ascent) * 0.35f, ink);
            text(min_label_, x0 - gap - float(min_label_.width), y1 - float(min_label_.ascent) * 0.65f, ink);
            text(unit_label_, std::min(x1 - float(unit_label_.width), x0), y0 - gap - float(unit_label_.height), ink);
        }
    }

    ~Overlay() override {
        if (vao_) glDeleteVertexArrays(1, &vao_);
    }

private:
    void rect(float x0, float y0, float x1, float y1) {
        prog_->set("u_rect", glm::vec4(x0, y0, x1, y1));
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
    Label time_label_, max_label_, min_label_, unit_label_, axis_label_[3];
    std::string time_unit_;
    float legend_min_ = 0, legend_max_ = 0;
    bool direction_ = false, timeless_ = false;
};

}  // namespace

PATHLET_PLUGIN("overlay", {
    sink->add(pathlet::PassTypeBuilder("overlay",
                                       "the animation time and the speed legend (colour bar, range, unit) over the "
                                       "finished image, as in the study's figures")
                  .param_bool("show", true, "draw the overlay (false: the image passes through unchanged)")
                  .param_bool("time", true, "the time label \"t = 4.50 s\", top left")
                  .param_bool("legend", true, "the speed colour bar with its range and unit, right edge")
                  .param_enum("colormap", "green_red", pathlet::lines::colormaps(),
                              "the line pass's colour map (tie both to one graph variable); direction shows an x/y/z key")
                  .param_float("speed_min", 0.0, -1.0, 1e9,
                               "speed at the bar's bottom, as the line pass's; <= 0: the data's 1st percentile")
                  .param_float("speed_max", 0.0, -1.0, 1e9,
                               "speed at the bar's top, as the line pass's; <= 0: the data's 99th percentile")
                  .param_string("speed_unit", "",
                                "unit shown with the legend; empty = the data's velocity unit where its file says it "
                                "(else the legend just says \"speed\")")
                  .param_float("font_px", 0.0, 0.0, 400.0, "text height in pixels; 0 = auto: output height / 28")
                  .param_string("font", "", "a TrueType/OpenType font file (.ttf, .otf, .ttc; nothing else is opened); empty = "
                                            "DejaVu Sans (share/pathlet/fonts, else fonts-dejavu-core); one that cannot be "
                                            "used gives a warning and the built-in font")
                  .param_color("text_color", {0.12f, 0.12f, 0.12f}, "colour of the text and the bar's frame")
                  .input_texture("color", "rgba8", "the finished image")
                  .output_texture("final", "rgba8", "the image with time and legend")
                  .make<Overlay>());
})
