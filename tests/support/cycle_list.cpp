#include "cycle_list.hpp"

#include <pathlet/pass.hpp>

#include <fstream>

namespace pathlet {
namespace {

struct CycleList : Pass {
    void execute(PassContext& ctx) override {
        glMemoryBarrier(GL_ALL_BARRIER_BITS);  // fill_list's atomics and node stores are done
        const Texture in = ctx.texture("heads"), out = ctx.texture("heads_out");
        glCopyImageSubData(in.id, GL_TEXTURE_2D, 0, 0, 0, 0, out.id, GL_TEXTURE_2D, 0, 0, 0, 0, in.width, in.height, 1);
        if (ctx.frame_index() != uint64_t(ctx.params().i("frame"))) return;
        const GLuint self = 0;  // node 0's `next` (the third word of its uvec4) is node 0
        glNamedBufferSubData(ctx.buffer("nodes").id, 2 * sizeof(GLuint), sizeof self, &self);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
};

}  // namespace

void add_cycle_list_pass(Runtime& rt) {
    if (rt.registry.find("test_cycle_list")) return;
    rt.registry.add(PassTypeBuilder("test_cycle_list", "makes the list holding node 0 cyclic in one frame (a test)")
                        .param_int("frame", 0, 0, 1000000, "the frame index whose list is made cyclic")
                        .input_texture("heads", "r32ui", "the lists' heads (fill_list filled them)")
                        .input_buffer("nodes", "the lists' nodes")
                        .output_texture("heads_out", "r32ui", "the heads, copied on for the resolve")
                        .make<CycleList>());
}

std::string write_cyclic_list_graph(const std::string& path, int frame) {
    std::ofstream(path) << R"({"extends": "variant2_exact", "name": "cyclic_list",
  "passes": [{"name": "cycle", "type": "test_cycle_list", "params": {"frame": )"
                        << frame << R"(},
              "inputs": {"heads": "heads", "nodes": "nodes"}},
             {"name": "resolve", "inputs": {"heads": "cycle.heads_out"}}]})";
    return path;
}

}  // namespace pathlet
