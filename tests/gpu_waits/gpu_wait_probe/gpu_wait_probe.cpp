// A test fixture for the count of waits for the GPU (engine/core/gpu_waits): a pass that clears
// its output and then makes one kind of GL call every frame, straight to libOpenGL as any pass
// plugin does. `call` picks it: one that waits (a synchronous read, glFinish, a blocking fence
// or query wait, a synchronised read map) or its asynchronous twin, which must not count.
#include <pathlet/gpu_fence.hpp>
#include <pathlet/plugin.hpp>

#include <vector>

namespace {

const std::vector<std::string> kCalls{
    "none",          "finish",        "get_buffer_sub_data", "get_named_buffer_sub_data", "read_pixels",
    "read_pixels_into_pack_buffer",   "get_texture_image",   "get_texture_image_into_pack_buffer",
    "client_wait",   "client_wait_poll", "server_wait",      "sdk_fence_wait",
    "query_result",  "query_result_after_available",         "map_read", "map_read_persistent", "map_write"};
enum class Call {
    none, finish, get_buffer_sub_data, get_named_buffer_sub_data, read_pixels, read_pixels_into_pack_buffer,
    get_texture_image, get_texture_image_into_pack_buffer, client_wait, client_wait_poll, server_wait, sdk_fence_wait,
    query_result, query_result_after_available, map_read, map_read_persistent, map_write
};
constexpr GLsizeiptr kBytes = 256;

class GpuWaitProbe : public pathlet::Pass {
public:
    ~GpuWaitProbe() override {
        glDeleteBuffers(1, &buffer_);
        glDeleteBuffers(1, &pack_);
        glDeleteQueries(1, &query_);
    }
    void setup(pathlet::PassContext& ctx) override {
        if (buffer_) return;
        glCreateBuffers(1, &buffer_);
        glNamedBufferStorage(buffer_, kBytes, nullptr,
                             GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT | GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT);
        pack_bytes_ = GLsizei(4 * ctx.output_size().x * ctx.output_size().y);
        glCreateBuffers(1, &pack_);
        glNamedBufferStorage(pack_, pack_bytes_, nullptr, 0);
        glCreateQueries(GL_ANY_SAMPLES_PASSED, 1, &query_);
    }
    void execute(pathlet::PassContext& ctx) override {
        ctx.bind_framebuffer({"color"});
        const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
        glClearBufferfv(GL_COLOR, 0, grey);
        const GLuint zero = 0;
        glClearNamedBufferData(buffer_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);  // the GPU writes it
        call(ctx, ctx.params().e<Call>("call"));
    }

private:
    void call(pathlet::PassContext& ctx, Call c) {
        const pathlet::Texture color = ctx.texture("color");
        std::vector<unsigned char> bytes(size_t(color.width) * size_t(color.height) * 4 + kBytes);
        switch (c) {
            case Call::none: break;
            case Call::finish: glFinish(); break;
            case Call::get_buffer_sub_data:
                glBindBuffer(GL_COPY_READ_BUFFER, buffer_);
                glGetBufferSubData(GL_COPY_READ_BUFFER, 0, kBytes, bytes.data());
                break;
            case Call::get_named_buffer_sub_data: glGetNamedBufferSubData(buffer_, 0, kBytes, bytes.data()); break;
            case Call::read_pixels: glReadPixels(0, 0, color.width, color.height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data()); break;
            case Call::read_pixels_into_pack_buffer:
                glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_);
                glReadPixels(0, 0, color.width, color.height, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
                glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
                break;
            case Call::get_texture_image:
                glGetTextureImage(color.id, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
                break;
            case Call::get_texture_image_into_pack_buffer:
                glBindBuffer(GL_PIXEL_PACK_BUFFER, pack_);
                glGetTextureImage(color.id, 0, GL_RGBA, GL_UNSIGNED_BYTE, pack_bytes_, nullptr);
                glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
                break;
            case Call::client_wait:
            case Call::client_wait_poll:
            case Call::server_wait: {
                GLsync s = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
                if (c == Call::server_wait) glWaitSync(s, 0, GL_TIMEOUT_IGNORED);
                else glClientWaitSync(s, GL_SYNC_FLUSH_COMMANDS_BIT, c == Call::client_wait ? 1'000'000'000 : 0);
                glDeleteSync(s);
                break;
            }
            case Call::sdk_fence_wait: pathlet::GpuFence::insert().wait(); break;  // libpathlet's own call
            case Call::query_result:
            case Call::query_result_after_available: {
                glBeginQuery(GL_ANY_SAMPLES_PASSED, query_);
                glEndQuery(GL_ANY_SAMPLES_PASSED);
                GLuint result = 0;
                if (c == Call::query_result_after_available)
                    for (GLint available = 0; !available;) glGetQueryObjectiv(query_, GL_QUERY_RESULT_AVAILABLE, &available);
                glGetQueryObjectuiv(query_, GL_QUERY_RESULT, &result);
                break;
            }
            case Call::map_read:
            case Call::map_read_persistent:
            case Call::map_write: {
                const GLbitfield access = c == Call::map_read              ? GL_MAP_READ_BIT
                                          : c == Call::map_read_persistent ? GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT
                                                                           : GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT;
                if (glMapNamedBufferRange(buffer_, 0, kBytes, access)) glUnmapNamedBuffer(buffer_);
                break;
            }
        }
    }

    GLuint buffer_ = 0, pack_ = 0, query_ = 0;
    GLsizei pack_bytes_ = 0;
};

}  // namespace

PATHLET_PLUGIN("gpu_wait_probe", {
    sink->add(pathlet::PassTypeBuilder("gpu_wait_probe",
                                       "test fixture: clears `color`, then makes one kind of GL call that waits for "
                                       "the GPU or not, every frame")
                  .param_enum("call", "none", kCalls, "the call: one that waits, or its asynchronous twin")
                  .param_bool("allowed", false, "the wait is declared (as an exact reference declares it)")
                  .waits_for_gpu("a test fixture that waits when told to", "allowed")
                  .output_texture("color", "rgba8", "grey")
                  .make<GpuWaitProbe>());
})
