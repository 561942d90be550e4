// clear_list: resets the per-pixel linked lists of OIT (the pipeline's first
// pass): every head pointer to "empty" and the node counter to 0.
#include <pathlet/oit.hpp>
#include <pathlet/plugin.hpp>

namespace {

class ClearList : public pathlet::Pass {
public:
    void execute(pathlet::PassContext& ctx) override {
        pathlet::oit::clear_lists(ctx.texture("heads").id, ctx.buffer("counter").id);
    }
};

}  // namespace

PATHLET_PLUGIN("clear_list", {
    sink->add(pathlet::PassTypeBuilder("clear_list", "resets OIT's per-pixel linked lists: head pointers and node counter")
                  .output_texture("heads", "r32ui", "per-pixel list head (node index), 0xffffffff = empty")
                  .output_buffer("counter", "node counter (uint), reset to 0", {.bytes = 16})
                  .make<ClearList>());
})
