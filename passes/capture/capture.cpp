// capture: writes its input to an image file every frame (a side effect: never culled).
// Graph `outputs` with a "capture" pattern do the same without a pass; this pass exists for
// writing intermediate results from inside a pipeline.
#include <pathlet/plugin.hpp>

namespace {

class Capture : public pathlet::Pass {
public:
    void execute(pathlet::PassContext& ctx) override {
        ctx.write_image("src", ctx.params().s("path"));
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
