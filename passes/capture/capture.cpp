// capture: writes its input to an image file every frame (a side effect: never culled).
// Graph `outputs` with a "capture" pattern do the same without a pass; this pass exists for
// writing intermediate results from inside a pipeline.
#include <pathlet/plugin.hpp>

#include "image_io.hpp"

#include <string>

namespace {

class Capture : public pathlet::Pass {
public:
    void execute(pathlet::PassContext& ctx) override {
        pathlet::Texture t = ctx.texture("src");
        pathlet::Image img = pathlet::read_texture(t.id, t.width, t.height, 0, 4);
        std::string file = pathlet::expand_pattern(ctx.params().s("path"), {{"pass", ctx.pass_name()}}, ctx.frame_index());
        pathlet::ensure_parent_dir(file);
        pathlet::write_image(file, img);
    }
};

pathlet::PassTypeInfo capture_type() {
    return pathlet::PassTypeBuilder("capture", "writes its input texture to an image file each frame (PNG, EXR, ...)")
        .param_string("path", "capture/{pass}_{frame:05}.png",
                      "file pattern: {pass}, {frame:05}; the extension picks the format (EXR keeps floats)")
        .input_texture("src", "any", "texture to write")
        .side_effect()
        .make<Capture>();
}

}  // namespace

PATHLET_PLUGIN("capture", { sink->add(capture_type()); })
