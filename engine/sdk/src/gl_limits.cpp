#include <pathlet/gl_limits.hpp>
#include <pathlet/shader.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace pathlet {

#define PATHLET_LIMIT(name, minimum) {#name, name, minimum}
#define PATHLET_SIZE(name, minimum) {#name, name, minimum, false}

const std::vector<GlLimit>& gl_limit_table() {
    static const std::vector<GlLimit> table = {
        // texture (sampler) units
        PATHLET_LIMIT(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, 80),
        PATHLET_LIMIT(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, 16),
        PATHLET_LIMIT(GL_MAX_GEOMETRY_TEXTURE_IMAGE_UNITS, 16),
        PATHLET_LIMIT(GL_MAX_TEXTURE_IMAGE_UNITS, 16),  // the fragment stage's
        PATHLET_LIMIT(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, 16),
        // image units and image uniforms
        PATHLET_LIMIT(GL_MAX_IMAGE_UNITS, 8),
        PATHLET_LIMIT(GL_MAX_COMBINED_IMAGE_UNIFORMS, 8),
        PATHLET_LIMIT(GL_MAX_VERTEX_IMAGE_UNIFORMS, 0),
        PATHLET_LIMIT(GL_MAX_GEOMETRY_IMAGE_UNIFORMS, 0),
        PATHLET_LIMIT(GL_MAX_FRAGMENT_IMAGE_UNIFORMS, 8),
        PATHLET_LIMIT(GL_MAX_COMPUTE_IMAGE_UNIFORMS, 8),
        // shader storage buffers
        PATHLET_LIMIT(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, 8),
        PATHLET_LIMIT(GL_MAX_COMBINED_SHADER_STORAGE_BLOCKS, 8),
        PATHLET_LIMIT(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, 0),
        PATHLET_LIMIT(GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS, 0),
        PATHLET_LIMIT(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, 8),
        PATHLET_LIMIT(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, 8),
        // uniform buffers
        PATHLET_LIMIT(GL_MAX_UNIFORM_BUFFER_BINDINGS, 84),
        PATHLET_LIMIT(GL_MAX_COMBINED_UNIFORM_BLOCKS, 70),
        PATHLET_LIMIT(GL_MAX_VERTEX_UNIFORM_BLOCKS, 14),
        PATHLET_LIMIT(GL_MAX_GEOMETRY_UNIFORM_BLOCKS, 14),
        PATHLET_LIMIT(GL_MAX_FRAGMENT_UNIFORM_BLOCKS, 14),
        PATHLET_LIMIT(GL_MAX_COMPUTE_UNIFORM_BLOCKS, 14),
        // what a fragment (or compute) stage may write: outputs + images + storage blocks
        PATHLET_LIMIT(GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES, 8),
        PATHLET_LIMIT(GL_MAX_DRAW_BUFFERS, 8),
        PATHLET_LIMIT(GL_MAX_COLOR_ATTACHMENTS, 8),
        PATHLET_LIMIT(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, 1024),
        // sizes: printed, always the context's
        PATHLET_SIZE(GL_MAX_TEXTURE_SIZE, 16384),
        PATHLET_SIZE(GL_MAX_3D_TEXTURE_SIZE, 2048),
        PATHLET_SIZE(GL_MAX_TEXTURE_BUFFER_SIZE, 65536),
        PATHLET_LIMIT(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 1 << 27),
        PATHLET_SIZE(GL_MAX_UNIFORM_BLOCK_SIZE, 16384),
    };
    return table;
}

#undef PATHLET_LIMIT
#undef PATHLET_SIZE

namespace {
size_t index_of(GLenum pname) {
    const auto& t = gl_limit_table();
    for (size_t i = 0; i < t.size(); ++i)
        if (t[i].pname == pname) return i;
    throw std::logic_error("gl_limits: limit 0x" + std::to_string(pname) + " is not in gl_limit_table()");
}

bool minimum_mode_from_env() {
    const char* v = std::getenv("PATHLET_GL_LIMITS");
    if (!v || !*v || std::strcmp(v, "context") == 0) return false;
    if (std::strcmp(v, "minimum") == 0) return true;
    throw std::runtime_error(std::string("PATHLET_GL_LIMITS='") + v +
                             "': expected 'minimum' (act as a minimal GL 4.5 driver) or 'context' (the default)");
}
}  // namespace

int GlLimits::context_value(GLenum pname) const { return context_.at(index_of(pname)); }

int GlLimits::get(GLenum pname) const {
    const size_t i = index_of(pname);
    const GlLimit& l = gl_limit_table()[i];
    return minimum_ && l.emulated ? l.minimum : context_.at(i);
}

std::string GlLimits::source(GLenum pname) const {
    const GlLimit& l = gl_limit_table()[index_of(pname)];
    if (minimum_ && l.emulated) return std::string(" (") + l.name + ": the GL 4.5 minimum, PATHLET_GL_LIMITS=minimum)";
    return std::string(" (") + l.name + ")";
}

const GlLimits& gl_limits() {
    // Queried once per renderer and mode: a few dozen glGet calls, not per program.
    static GlLimits cached;
    static std::string cached_renderer;
    static bool queried = false;
    const bool minimum = minimum_mode_from_env();
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer = r ? r : "";
    if (!queried || renderer != cached_renderer) {
        cached.context_.clear();
        for (const GlLimit& l : gl_limit_table()) {
            GLint64 v = 0;
            glGetInteger64v(l.pname, &v);
            cached.context_.push_back(int(std::min<GLint64>(v, std::numeric_limits<int>::max())));
        }
        cached_renderer = renderer;
        queried = true;
    }
    cached.minimum_ = minimum;
    return cached;
}

std::string at_picture_size(int width, int height) {
    return "at " + std::to_string(width) + "x" + std::to_string(height);
}

void check_storage_block(size_t bytes, const std::string& what, const std::string& at, const std::string& hint) {
    const GlLimits& l = gl_limits();
    const size_t limit = size_t(std::max(l.get(GL_MAX_SHADER_STORAGE_BLOCK_SIZE), 0));
    if (bytes <= limit) return;
    auto mib = [](size_t b) {
        char s[32];
        std::snprintf(s, sizeof s, "%.1f MiB", double(b) / 1048576.0);
        return std::string(s);
    };
    throw std::runtime_error(what + " needs " + mib(bytes) + " in one storage block " + at + ", above the " + mib(limit) +
                             " this context allows" +
                             l.source(GL_MAX_SHADER_STORAGE_BLOCK_SIZE) + (hint.empty() ? "" : "; " + hint));
}

// ---- per-program check ----------------------------------------------------------------------

namespace {

enum Stage { kVertex, kGeometry, kFragment, kCompute, kStages };
const char* const kStageName[kStages] = {"vertex", "geometry", "fragment", "compute"};
const GLenum kReferencedBy[kStages] = {GL_REFERENCED_BY_VERTEX_SHADER, GL_REFERENCED_BY_GEOMETRY_SHADER,
                                       GL_REFERENCED_BY_FRAGMENT_SHADER, GL_REFERENCED_BY_COMPUTE_SHADER};

struct PerStage {
    int n[kStages] = {};
    int combined = 0;
};

}  // namespace

bool is_image_type(GLenum t) {
    switch (t) {
        case GL_IMAGE_1D: case GL_IMAGE_2D: case GL_IMAGE_3D: case GL_IMAGE_BUFFER: case GL_IMAGE_2D_ARRAY:
        case GL_IMAGE_CUBE: case GL_IMAGE_2D_RECT:
        case GL_INT_IMAGE_1D: case GL_INT_IMAGE_2D: case GL_INT_IMAGE_3D: case GL_INT_IMAGE_BUFFER:
        case GL_INT_IMAGE_2D_ARRAY: case GL_INT_IMAGE_CUBE: case GL_INT_IMAGE_2D_RECT:
        case GL_UNSIGNED_INT_IMAGE_1D: case GL_UNSIGNED_INT_IMAGE_2D: case GL_UNSIGNED_INT_IMAGE_3D:
        case GL_UNSIGNED_INT_IMAGE_BUFFER: case GL_UNSIGNED_INT_IMAGE_2D_ARRAY: case GL_UNSIGNED_INT_IMAGE_CUBE:
        case GL_UNSIGNED_INT_IMAGE_2D_RECT: return true;
        default: return false;
    }
}
bool is_sampler_type(GLenum t) {
    switch (t) {
        case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_2D_ARRAY:
        case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_BUFFER: case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_SHADOW:
        case GL_SAMPLER_2D_MULTISAMPLE: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_CUBE_SHADOW:
        case GL_INT_SAMPLER_1D: case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_INT_SAMPLER_BUFFER:
        case GL_INT_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_CUBE: case GL_INT_SAMPLER_2D_RECT:
        case GL_UNSIGNED_INT_SAMPLER_1D: case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_3D:
        case GL_UNSIGNED_INT_SAMPLER_BUFFER: case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_CUBE:
        case GL_UNSIGNED_INT_SAMPLER_2D_RECT: return true;
        default: return false;
    }
}

namespace {

// Which stages the program has, from its attached shaders.
void stages_of(GLuint prog, bool has[kStages]) {
    GLint n = 0;
    glGetProgramiv(prog, GL_ATTACHED_SHADERS, &n);
    std::vector<GLuint> shaders(size_t(std::max(n, 0)));
    if (n > 0) glGetAttachedShaders(prog, n, nullptr, shaders.data());
    for (GLuint s : shaders) {
        GLint type = 0;
        glGetShaderiv(s, GL_SHADER_TYPE, &type);
        if (type == GL_VERTEX_SHADER) has[kVertex] = true;
        if (type == GL_GEOMETRY_SHADER) has[kGeometry] = true;
        if (type == GL_FRAGMENT_SHADER) has[kFragment] = true;
        if (type == GL_COMPUTE_SHADER) has[kCompute] = true;
    }
}

// Counts the resources of `interface` per stage (uniforms: those `keep` accepts by type).
PerStage count(GLuint prog, GLenum interface, int last_stage, bool (*keep)(GLenum), std::vector<int>* bindings) {
    PerStage c;
    GLint n = 0;
    glGetProgramInterfaceiv(prog, interface, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n; ++i) {
        int size = 1;
        if (interface == GL_UNIFORM) {
            const GLenum props[] = {GL_TYPE, GL_ARRAY_SIZE, GL_BLOCK_INDEX};
            GLint v[3] = {};
            glGetProgramResourceiv(prog, interface, GLuint(i), 3, props, 3, nullptr, v);
            if (v[2] != -1 || (keep && !keep(GLenum(v[0])))) continue;
            size = std::max(1, v[1]);
        } else if (bindings) {
            const GLenum prop = GL_BUFFER_BINDING;
            GLint b = 0;
            glGetProgramResourceiv(prog, interface, GLuint(i), 1, &prop, 1, nullptr, &b);
            bindings->push_back(b);
        }
        bool any = false;
        for (int s = 0; s < kStages; ++s) {
            GLint ref = 0;
            glGetProgramResourceiv(prog, interface, GLuint(i), 1, &kReferencedBy[s], 1, nullptr, &ref);
            if (ref) {
                c.n[s] += size;
                any = true;
            }
        }
        // Mesa flags no stage for a storage block used only through atomic functions (fill_list's
        // counter): count it where such writes happen, the program's last stage.
        if (!any && interface != GL_UNIFORM && last_stage >= 0) {
            c.n[last_stage] += size;
            any = true;
        }
        if (any) c.combined += size;
    }
    return c;
}

// Fragment outputs, counting array elements: they take draw buffers and output resources.
int fragment_outputs(GLuint prog) {
    GLint n = 0, total = 0;
    glGetProgramInterfaceiv(prog, GL_PROGRAM_OUTPUT, GL_ACTIVE_RESOURCES, &n);
    for (GLint i = 0; i < n; ++i) {
        const GLenum props[] = {GL_ARRAY_SIZE, GL_REFERENCED_BY_FRAGMENT_SHADER};
        GLint v[2] = {};
        glGetProgramResourceiv(prog, GL_PROGRAM_OUTPUT, GLuint(i), 2, props, 2, nullptr, v);
        if (v[1]) total += std::max(1, v[0]);
    }
    return total;
}

}  // namespace

void check_program_limits(GLuint prog, const std::string& what) {
    const GlLimits& L = gl_limits();
    bool has[kStages] = {};
    stages_of(prog, has);
    int last = -1;
    for (int s = 0; s < kStages; ++s)
        if (has[s]) last = s;
    auto fail = [&](const std::string& need, int asked, GLenum limit) {
        throw ShaderError("program (" + what + ") " + need + " " + std::to_string(asked) + "; this context allows " +
                          std::to_string(L.get(limit)) + L.source(limit));
    };
    auto check = [&](const PerStage& c, const char* kind, const GLenum per_stage[kStages], GLenum combined) {
        for (int s = 0; s < kStages; ++s)
            if (has[s] && c.n[s] > L.get(per_stage[s]))
                fail(std::string("uses ") + kind + " in its " + kStageName[s] + " stage:", c.n[s], per_stage[s]);
        if (combined && c.combined > L.get(combined)) fail(std::string("uses ") + kind + " in all:", c.combined, combined);
    };

    // Per kind of resource: what counts, its per-stage and combined limits, its binding limit.
    struct Kind {
        GLenum interface;
        bool (*keep)(GLenum type);
        const char* what;
        GLenum per_stage[kStages], combined, bindings;
    };
    static const Kind kinds[] = {
        {GL_UNIFORM, is_sampler_type, "samplers",
         {GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, GL_MAX_GEOMETRY_TEXTURE_IMAGE_UNITS, GL_MAX_TEXTURE_IMAGE_UNITS,
          GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS},
         GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, 0},
        {GL_UNIFORM, is_image_type, "image uniforms",
         {GL_MAX_VERTEX_IMAGE_UNIFORMS, GL_MAX_GEOMETRY_IMAGE_UNIFORMS, GL_MAX_FRAGMENT_IMAGE_UNIFORMS,
          GL_MAX_COMPUTE_IMAGE_UNIFORMS},
         GL_MAX_COMBINED_IMAGE_UNIFORMS, 0},
        {GL_SHADER_STORAGE_BLOCK, nullptr, "shader storage blocks",
         {GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS,
          GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS},
         GL_MAX_COMBINED_SHADER_STORAGE_BLOCKS, GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS},
        {GL_UNIFORM_BLOCK, nullptr, "uniform blocks",
         {GL_MAX_VERTEX_UNIFORM_BLOCKS, GL_MAX_GEOMETRY_UNIFORM_BLOCKS, GL_MAX_FRAGMENT_UNIFORM_BLOCKS,
          GL_MAX_COMPUTE_UNIFORM_BLOCKS},
         GL_MAX_COMBINED_UNIFORM_BLOCKS, GL_MAX_UNIFORM_BUFFER_BINDINGS},
    };
    PerStage counted[4];
    for (size_t k = 0; k < 4; ++k) {
        const Kind& kind = kinds[k];
        std::vector<int> bindings;
        counted[k] = count(prog, kind.interface, last, kind.keep, kind.bindings ? &bindings : nullptr);
        check(counted[k], kind.what, kind.per_stage, kind.combined);
        for (int b : bindings)
            if (b >= L.get(kind.bindings)) fail(std::string("binds one of its ") + kind.what + " to binding point", b, kind.bindings);
    }
    const PerStage &images = counted[1], &storage = counted[2];

    // The spec's rule for a whole program: active images + storage blocks + fragment outputs.
    const int outputs = has[kFragment] ? fragment_outputs(prog) : 0;
    if (outputs > L.get(GL_MAX_DRAW_BUFFERS)) fail("writes fragment outputs:", outputs, GL_MAX_DRAW_BUFFERS);
    const int writes = outputs + images.combined + storage.combined;
    if (writes > L.get(GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES))
        fail("uses fragment outputs, images and storage blocks together (" + std::to_string(outputs) + " + " +
                 std::to_string(images.combined) + " + " + std::to_string(storage.combined) + "):",
             writes, GL_MAX_COMBINED_SHADER_OUTPUT_RESOURCES);
    if (has[kCompute]) {
        GLint size[3] = {};
        glGetProgramiv(prog, GL_COMPUTE_WORK_GROUP_SIZE, size);
        const int invocations = size[0] * size[1] * size[2];
        if (invocations > L.get(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS))
            fail("asks for work groups of invocations:", invocations, GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    }
}

}  // namespace pathlet
