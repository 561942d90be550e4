#include <pathlet/shader.hpp>
#include <pathlet/gl_limits.hpp>

#include <pathlet/text.hpp>

#include "shader_interlock.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

GLenum ShaderStage::of_extension(const std::string& file) {
    const std::string ext = fs::path(file).extension().string();
    if (ext == ".vert") return GL_VERTEX_SHADER;
    if (ext == ".geom") return GL_GEOMETRY_SHADER;
    if (ext == ".frag") return GL_FRAGMENT_SHADER;
    if (ext == ".comp") return GL_COMPUTE_SHADER;
    if (ext == ".tesc") return GL_TESS_CONTROL_SHADER;
    if (ext == ".tese") return GL_TESS_EVALUATION_SHADER;
    throw ShaderError(file + ": unknown shader stage (use .vert .geom .frag .comp)");
}

namespace {

// Uniform names declared in a source: "uniform vec3 a, b[4];" gives a and b. Blocks
// ("uniform Name { ... }") are skipped: their members are not set by name.
void collect_uniforms(const std::string& src, std::set<std::string>& out) {
    static const std::regex decl(R"(\buniform\s+(?:(?:lowp|mediump|highp)\s+)?\w+\s+([^;{]+);)");
    for (auto it = std::sregex_iterator(src.begin(), src.end(), decl); it != std::sregex_iterator(); ++it) {
        std::stringstream names((*it)[1].str());
        std::string n;
        while (std::getline(names, n, ',')) {
            size_t a = n.find_first_not_of(" \t\n"), b = n.find_first_of(" \t\n[=", a);
            if (a != std::string::npos) out.insert(n.substr(a, b == std::string::npos ? b : b - a));
        }
    }
}

// PATHLET_SHADER_DUMP=DIR: every object's source as the driver gets it (defines, includes and
// #line expanded), DIR/NNNN-K-FILE, for a driver's message that names only its own lines.
void dump_sources(const std::vector<ShaderUnit>& units) {
    const char* dir = std::getenv("PATHLET_SHADER_DUMP");
    if (!dir || !*dir) return;
    static int program = 0;
    ++program;
    std::error_code ec;
    fs::create_directories(dir, ec);
    for (size_t k = 0; k < units.size(); ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "%04d-%zu-", program, k);
        std::ofstream(fs::path(dir) / (name + fs::path(units[k].path).filename().string())) << units[k].src;
    }
}

std::string info_log(GLuint object, bool program) {
    GLint len = 0;
    (program ? glGetProgramiv : glGetShaderiv)(object, GL_INFO_LOG_LENGTH, &len);
    std::string log(size_t(std::max(len, 1)), '\0');
    (program ? glGetProgramInfoLog : glGetShaderInfoLog)(object, len, nullptr, log.data());
    return log.c_str();
}

}  // namespace

ShaderProgram ShaderProgram::from_files(const std::vector<std::string>& names, const ShaderSource& source,
                                        const std::vector<std::string>& defines) {
    std::vector<ShaderStage> stages;
    for (const auto& n : names) {
        std::string file = source.find(n);  // the name is checked before its extension
        stages.push_back({ShaderStage::of_extension(n), {std::move(file)}});
    }
    return build(stages, source, defines);
}

ShaderProgram ShaderProgram::build(const std::vector<ShaderStage>& stages, const ShaderSource& source,
                                   const std::vector<std::string>& defines) {
    std::vector<ShaderUnit> units;
    for (const auto& st : stages) {
        if (st.files.empty()) throw ShaderError("a shader stage without files");
        ShaderUnit u{st.files.back(), "", st.files, {}, st.stage};
        u.src = source.compose(st.files, defines, u.numbered);
        units.push_back(std::move(u));
    }
    merge_interlocked_fragments(units, source);
    dump_sources(units);
    ShaderProgram prog;
    prog.id_ = glCreateProgram();
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    for (const ShaderUnit& u : units) {
        collect_uniforms(u.src, prog.declared_);
        prog.files_ += (prog.files_.empty() ? "" : ", ") + fs::path(u.path).filename().string();
        GLuint sh = glCreateShader(u.stage);
        shaders.push_back(sh);
        const char* p = u.src.c_str();
        glShaderSource(sh, 1, &p, nullptr);
        glCompileShader(sh);
        GLint ok = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            const std::string log = info_log(sh, false);
            cleanup();
            throw ShaderError("GLSL compile error in " + u.path + ":\n" + ShaderSource::map_log(log, u.numbered) +
                              u.merge_note);
        }
        glAttachShader(prog.id_, sh);
    }
    glLinkProgram(prog.id_);
    cleanup();
    GLint ok = 0;
    glGetProgramiv(prog.id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        std::string list;
        for (const auto& u : units) list += (list.empty() ? "" : ", ") + fs::path(u.path).filename().string();
        throw ShaderError("GLSL link error in program (" + list + "):\n" + info_log(prog.id_, true));
    }
    // What a minimal GL 4.5 driver would refuse fails here on any driver (pathlet/gl_limits.hpp).
    check_program_limits(prog.id_, prog.files_);
    prog.reflect();
    for (const auto& u : units)
        if (u.stage == GL_COMPUTE_SHADER) glGetProgramiv(prog.id_, GL_COMPUTE_WORK_GROUP_SIZE, &prog.local_size_.x);
    return prog;
}

// Active uniforms of the default block; samplers and images get units 0, 1, ... each in
// GL's order (what a layout(binding) in the source said is replaced: units are the engine's).
void ShaderProgram::reflect() {
    uniforms_.clear();
    GLint count = 0;
    glGetProgramInterfaceiv(id_, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    int samplers = 0, images = 0;
    for (GLint i = 0; i < count; ++i) {
        const GLenum props[] = {GL_NAME_LENGTH, GL_TYPE, GL_ARRAY_SIZE, GL_LOCATION, GL_BLOCK_INDEX};
        GLint v[5] = {};
        glGetProgramResourceiv(id_, GL_UNIFORM, GLuint(i), 5, props, 5, nullptr, v);
        if (v[4] != -1) continue;  // a block member: set through its buffer
        std::string name(size_t(std::max(v[0], 1)), '\0');
        glGetProgramResourceName(id_, GL_UNIFORM, GLuint(i), v[0], nullptr, name.data());
        name.resize(std::strlen(name.c_str()));
        if (name.size() > 3 && name.compare(name.size() - 3, 3, "[0]") == 0) name.resize(name.size() - 3);
        Uniform u{name, GLenum(v[1]), v[2], v[3]};
        u.image = is_image_type(u.type);
        u.opaque = u.image || is_sampler_type(u.type);
        uniforms_.push_back(u);
        if (u.opaque) {
            int& next = u.image ? images : samplers;
            set_unit(u.name, next);
            next += std::max(1, u.size);
        }
    }
    blocks_.clear();
    glGetProgramInterfaceiv(id_, GL_UNIFORM_BLOCK, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count; ++i) {
        GLint len = 0;
        const GLenum prop = GL_NAME_LENGTH;
        glGetProgramResourceiv(id_, GL_UNIFORM_BLOCK, GLuint(i), 1, &prop, 1, nullptr, &len);
        std::string name(size_t(std::max(len, 1)), '\0');
        glGetProgramResourceName(id_, GL_UNIFORM_BLOCK, GLuint(i), len, nullptr, name.data());
        name.resize(std::strlen(name.c_str()));
        glUniformBlockBinding(id_, GLuint(i), GLuint(i));
        blocks_.push_back({name, int(i)});
    }
}

int ShaderProgram::block_binding(const std::string& name) const {
    for (const auto& b : blocks_)
        if (b.name == name) return b.binding;
    return -1;
}

const ShaderProgram::Uniform* ShaderProgram::uniform(const std::string& name) const {
    for (const auto& u : uniforms_)
        if (u.name == name) return &u;
    return nullptr;
}

void ShaderProgram::set_unit(const std::string& name, int unit) {
    for (auto& u : uniforms_)
        if (u.name == name && u.opaque) {
            u.unit = unit;
            std::vector<GLint> units(size_t(std::max(1, u.size)));
            for (size_t k = 0; k < units.size(); ++k) units[k] = unit + GLint(k);
            glProgramUniform1iv(id_, u.location, GLsizei(units.size()), units.data());
            return;
        }
}

const ShaderProgram::Uniform& ShaderProgram::opaque_uniform(const std::string& name) const {
    static const Uniform inactive;
    if (const Uniform* u = uniform(name)) {
        if (u->opaque) return *u;
        throw ShaderError("program (" + files_ + "): '" + name + "' is not a sampler or image");
    }
    loc(name);  // throws for a name no source declares (a typo)
    return inactive;
}

void ShaderProgram::bind_texture(const std::string& name, GLuint texture) const {
    const Uniform& u = opaque_uniform(name);
    if (u.unit >= 0) glBindTextureUnit(GLuint(u.unit), texture);
}

void ShaderProgram::bind_image(const std::string& name, GLuint texture, GLenum format, GLenum access, int level) const {
    const Uniform& u = opaque_uniform(name);
    if (u.unit >= 0) glBindImageTexture(GLuint(u.unit), texture, level, GL_FALSE, 0, access, format);
}

ShaderProgram::ShaderProgram(ShaderProgram&& o) noexcept
    : id_(o.id_), uniforms_(std::move(o.uniforms_)), blocks_(std::move(o.blocks_)), locs_(std::move(o.locs_)), declared_(std::move(o.declared_)), files_(std::move(o.files_)),
      local_size_(o.local_size_) {
    o.id_ = 0;
}
ShaderProgram& ShaderProgram::operator=(ShaderProgram&& o) noexcept {
    if (this != &o) {
        if (id_) glDeleteProgram(id_);
        id_ = o.id_;
        uniforms_ = std::move(o.uniforms_);
        blocks_ = std::move(o.blocks_);
        locs_ = std::move(o.locs_);
        declared_ = std::move(o.declared_);
        files_ = std::move(o.files_);
        local_size_ = o.local_size_;
        o.id_ = 0;
    }
    return *this;
}
ShaderProgram::~ShaderProgram() {
    if (id_) glDeleteProgram(id_);
}

GLint ShaderProgram::loc(const std::string& uniform) const {
    auto it = locs_.find(uniform);
    if (it != locs_.end()) return it->second;
    GLint l = glGetUniformLocation(id_, uniform.c_str());
    if (l < 0 && !declares(uniform)) {
        std::vector<std::string> names(declared_.begin(), declared_.end());
        throw ShaderError("program (" + files_ + ") has no uniform '" + uniform + "'" +
                          text::did_you_mean(uniform, names) + " (a misspelt name would silently do nothing)");
    }
    locs_[uniform] = l;
    return l;
}

bool ShaderProgram::declares(const std::string& uniform) const {
    // "u_light[2].dir" is declared when "u_light" is.
    return declared_.count(uniform.substr(0, uniform.find_first_of("[."))) > 0;
}

void ShaderProgram::set(const std::string& n, int v) const { glProgramUniform1i(id_, loc(n), v); }
void ShaderProgram::set(const std::string& n, float v) const { glProgramUniform1f(id_, loc(n), v); }
void ShaderProgram::set(const std::string& n, glm::vec2 v) const { glProgramUniform2f(id_, loc(n), v.x, v.y); }
void ShaderProgram::set(const std::string& n, glm::vec3 v) const { glProgramUniform3f(id_, loc(n), v.x, v.y, v.z); }
void ShaderProgram::set(const std::string& n, glm::vec4 v) const {
    glProgramUniform4f(id_, loc(n), v.x, v.y, v.z, v.w);
}
void ShaderProgram::set(const std::string& n, glm::ivec2 v) const { glProgramUniform2i(id_, loc(n), v.x, v.y); }
void ShaderProgram::set(const std::string& n, glm::ivec4 v) const { glProgramUniform4i(id_, loc(n), v.x, v.y, v.z, v.w); }
void ShaderProgram::set(const std::string& n, const glm::mat4& v) const {
    glProgramUniformMatrix4fv(id_, loc(n), 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace pathlet
