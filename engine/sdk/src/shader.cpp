#include <pathlet/shader.hpp>
#include <pathlet/gl_limits.hpp>

#include <pathlet/text.hpp>

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

std::string find_shader_file(const std::string& name, const std::vector<std::string>& dirs) {
    // A hook file the user named by its path (--set, Python) is on the search path as that file
    // itself: found by that path, and only then.
    if (fs::path(name).is_absolute()) {
        for (const auto& d : dirs) {
            std::error_code ec;
            if (d == name && fs::is_regular_file(d, ec)) return d;
        }
        throw ShaderError("shader name '" + name +
                          "' refused: a shader is a file name (no '/', not '..') looked up on the shader path; a "
                          "path only when you named that file for a hook (--set PASS.color_hook=PATH, Graph.set in "
                          "Python)");
    }
    // Otherwise a shader is a file name looked up on the shader path, never a path: a graph names
    // shaders (fullscreen.shader), and "/etc/passwd" or "../../secret" must not reach another file.
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
        throw ShaderError("shader name '" + name +
                          "' refused: a shader is a file name (no '/', not '..') looked up on the shader path");
    for (const auto& d : dirs) {
        fs::path p = fs::path(d) / name;
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) return p.string();
    }
    std::string msg = "shader file '" + name + "' not found; searched:";
    for (const auto& d : dirs) msg += "\n  " + d;
    throw ShaderError(msg);
}

std::string include_target(const std::string& line) {
    static const std::regex include_re(R"(^\s*#\s*include\s+[<"]([^">]+)[">]\s*$)");
    std::smatch m;
    return std::regex_match(line, m, include_re) ? m[1].str() : std::string();
}

namespace {

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShaderError(path + ": cannot read");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool is_version_line(const std::string& line) {
    static const std::regex version_re(R"(^\s*#\s*version\b.*$)");
    return std::regex_match(line, version_re);
}

// Where each file's lines are numbered: file k's line n is "#line k*kLinesPerFile+n k". The
// source-string number alone is not enough: Mesa reports source 0 for errors in compound
// expressions (a wrong struct field, a wrong argument type: its parser's default location
// drops the number), so the line itself says the file too (map_log decodes both).
constexpr long kLinesPerFile = 1000000;
std::string line_directive(long line, size_t file) {
    return "#line " + std::to_string(long(file) * kLinesPerFile + line) + " " + std::to_string(file) + "\n";
}

// Inlines #include "x" recursively. Each file gets a source-string number for #line, so the
// compiler's messages can be mapped back to the file names in `files`. A file's own #version
// line becomes an empty line (compose() puts one version line first), so its lines keep their
// numbers.
std::string expand(const std::string& path, const std::vector<std::string>& dirs, std::vector<std::string>& files,
                   int depth) {
    if (depth > 16) throw ShaderError(path + ": #include nested too deeply (a cycle?)");
    int id = int(files.size());
    files.push_back(path);
    std::istringstream in(read_text(path));
    std::ostringstream out;
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
        ++n;
        if (const std::string name = include_target(line); !name.empty()) {
            std::vector<std::string> search = {fs::path(path).parent_path().string()};
            search.insert(search.end(), dirs.begin(), dirs.end());
            std::string inc;
            try {
                inc = find_shader_file(name, search);
            } catch (const ShaderError& e) {
                throw ShaderError(path + ":" + std::to_string(n) + ": " + e.what());
            }
            out << line_directive(1, files.size());
            out << expand(inc, dirs, files, depth + 1);
            out << line_directive(n + 1, size_t(id));
        } else if (depth == 0 && is_version_line(line)) {
            out << "\n";
        } else {
            out << line << "\n";
        }
    }
    return out.str();
}

// One stage's source from its files (the last is the stage's own; those before it are included
// first, as the line kit gives a hook its definitions): the version line first — the first
// that one of the files has, else the engine's — then the program's defines, then each file
// under its own source-string number.
std::string compose(const std::vector<std::string>& paths, const std::vector<std::string>& dirs,
                    std::vector<std::string>& files, const std::vector<std::string>& defines) {
    std::string version = "#version 450 core";
    for (auto it = paths.rbegin(); it != paths.rend(); ++it) {  // the stage's own file decides
        std::istringstream in(read_text(*it));
        std::string line;
        bool found = false;
        while (!found && std::getline(in, line)) found = is_version_line(line);
        if (found) {
            version = line;
            break;
        }
    }
    std::ostringstream out;
    out << version << "\n";
    for (const auto& d : defines) out << "#define " << d << "\n";
    for (const auto& p : paths) {
        out << line_directive(1, files.size());
        out << expand(p, dirs, files, 0);
    }
    return out.str();
}

// "frag:line_hooks.glsl+/home/me/fade.glsl" -> stage "frag", files {"line_hooks.glsl",
// "/home/me/fade.glsl"}. A prefix counts as a stage only when it names one, and a '+' only
// after a plain file name with a shader extension, so a path with ':' or '+' stays whole.
struct Entry {
    std::string stage;               // "" = by the extension of the last file
    std::vector<std::string> files;
};
Entry parse_entry(const std::string& entry) {
    static const std::regex stage_re(R"(^(vert|geom|frag|comp|tesc|tese):)");
    static const std::regex prelude_re(R"(^([^/+:]+\.(glsl|vert|geom|frag|comp))\+)");
    Entry e;
    std::string rest = entry;
    std::smatch m;
    if (std::regex_search(rest, m, stage_re)) e.stage = m[1].str(), rest = m.suffix().str();
    while (std::regex_search(rest, m, prelude_re)) e.files.push_back(m[1].str()), rest = m.suffix().str();
    e.files.push_back(rest);
    return e;
}

// Rewrites "0:12(3): error: ..." (Mesa) and "0(12) : error ..." (NVIDIA) into "file:12: error: ...",
// the file from the line's number where it holds one (line_directive), else from the source string.
std::string map_log(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
    static const std::regex nv(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream in(log);
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        // "file:line" of source string `idx` and line `at` as the compiler reports them.
        auto place = [&](const std::string& idx, const std::string& at) {
            size_t i = std::stoul(idx);
            long n = std::stol(at);
            if (n >= kLinesPerFile) i = size_t(n / kLinesPerFile), n %= kLinesPerFile;
            return (i < files.size() ? files[i] : "<source " + std::to_string(i) + ">") + ":" + std::to_string(n);
        };
        if (std::regex_match(line, m, mesa))
            out << place(m[1], m[2]) << ":" << m[3] << ": " << m[4] << "\n";
        else if (std::regex_match(line, m, nv))
            out << place(m[1], m[2]) << ": " << m[3] << "\n";
        else if (!line.empty())
            out << line << "\n";
    }
    return out.str();
}

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

GLenum stage_of(const std::string& file) {
    std::string ext = fs::path(file).extension().string();
    if (ext == ".vert") return GL_VERTEX_SHADER;
    if (ext == ".geom") return GL_GEOMETRY_SHADER;
    if (ext == ".frag") return GL_FRAGMENT_SHADER;
    if (ext == ".comp") return GL_COMPUTE_SHADER;
    if (ext == ".tesc") return GL_TESS_CONTROL_SHADER;
    if (ext == ".tese") return GL_TESS_EVALUATION_SHADER;
    throw ShaderError(file + ": unknown shader stage (use .vert .geom .frag .comp)");
}

// A program whose fragment stage uses the fragment shader interlock (GL_ARB_fragment_shader_
// interlock: MLAB) gets that stage as one object: the other fragment objects (a colour hook) are
// appended to the one that declares the interlock. NVIDIA (580, H200) links an interlocked stage of
// several objects into code without the interlock and fails ("FSIB: invalid statement"), whichever
// objects declare it; as one object it links. The appended files keep their own source-string
// numbers, so messages still name them; their #version and the defines are not repeated.
template <class Units>
void merge_interlocked_fragments(Units& units, const std::vector<std::string>& dirs) {
    static const std::regex decl(R"(^\s*layout\s*\(\s*(pixel|sample)_interlock_(un)?ordered\s*\)\s*in\s*;)");
    auto declares = [](const std::string& src) {
        std::istringstream in(src);
        for (std::string line; std::getline(in, line);)
            if (std::regex_search(line, decl)) return true;
        return false;
    };
    size_t m = 0;
    while (m < units.size() && !(units[m].stage == GL_FRAGMENT_SHADER && declares(units[m].src))) ++m;
    if (m == units.size()) return;
    for (size_t k = 0; k < units.size(); ++k) {
        if (k == m || units[k].stage != GL_FRAGMENT_SHADER) continue;
        const std::string more = compose(units[k].paths, dirs, units[m].files, {});
        units[m].src += more.substr(more.find('\n') + 1);  // without its version line
        units[m].path.append("+").append(fs::path(units[k].path).filename().string());
    }
    Units kept;
    for (size_t k = 0; k < units.size(); ++k)
        if (k == m || units[k].stage != GL_FRAGMENT_SHADER) kept.push_back(std::move(units[k]));
    units = std::move(kept);
}

// PATHLET_SHADER_DUMP=DIR: every stage's source as the driver gets it (defines, includes and
// #line expanded), DIR/NNNN-K-FILE, for a driver's message that names only its own lines.
template <class Units>
void dump_sources(const Units& units) {
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

}  // namespace

ShaderProgram ShaderProgram::from_files(const std::vector<std::string>& names, const std::vector<std::string>& dirs,
                                        const std::vector<std::string>& defines) {
    ShaderProgram prog;
    prog.id_ = glCreateProgram();
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    struct Unit {
        std::string path, src;
        std::vector<std::string> paths, files;
        GLenum stage;
    };
    std::vector<Unit> units;
    for (const auto& text : names) {
        const Entry entry = parse_entry(text);
        std::vector<std::string> paths;
        for (const auto& f : entry.files) paths.push_back(find_shader_file(f, dirs));
        Unit u{paths.back(), "", paths, {}, 0};
        u.src = compose(paths, dirs, u.files, defines);
        u.stage = stage_of(entry.stage.empty() ? u.path : "stage." + entry.stage);
        units.push_back(std::move(u));
    }
    merge_interlocked_fragments(units, dirs);
    dump_sources(units);
    for (auto& [path, src, paths, files, stage] : units) {
        collect_uniforms(src, prog.declared_);
        prog.files_ += (prog.files_.empty() ? "" : ", ") + fs::path(path).filename().string();
        GLuint sh = glCreateShader(stage);
        shaders.push_back(sh);
        const char* p = src.c_str();
        glShaderSource(sh, 1, &p, nullptr);
        glCompileShader(sh);
        GLint ok = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint len = 0;
            glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
            std::string log(size_t(std::max(len, 1)), '\0');
            glGetShaderInfoLog(sh, len, nullptr, log.data());
            cleanup();
            throw ShaderError("GLSL compile error in " + path + ":\n" + map_log(log.c_str(), files));
        }
        glAttachShader(prog.id_, sh);
    }
    glLinkProgram(prog.id_);
    cleanup();
    GLint ok = 0;
    glGetProgramiv(prog.id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(prog.id_, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(std::max(len, 1)), '\0');
        glGetProgramInfoLog(prog.id_, len, nullptr, log.data());
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw ShaderError("GLSL link error in program (" + list + "):\n" + log.c_str());
    }
    // What a minimal GL 4.5 driver would refuse fails here on any driver (pathlet/gl_limits.hpp).
    check_program_limits(prog.id_, prog.files_);
    prog.reflect();
    bool compute = false;
    for (const auto& entry : names) {
        const size_t colon = entry.find(':');
        compute = compute || stage_of(colon == std::string::npos ? entry : "stage." + entry.substr(0, colon)) == GL_COMPUTE_SHADER;
    }
    if (compute) glGetProgramiv(prog.id_, GL_COMPUTE_WORK_GROUP_SIZE, &prog.local_size_.x);
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
