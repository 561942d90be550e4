// GLSL programs from shader files: each shader object's files found on a ShaderSource's path
// (or given found, as a hook is), `#include "file"` inlined, a #version line of the file's own or
// the engine's (450 core) first. Each file gets a number in #line directives, so compile errors
// read "<file>:<line>: <message>" (ShaderError).
#pragma once

#include <pathlet/gl.hpp>
#include <pathlet/shader_source.hpp>

#include <glm/glm.hpp>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace pathlet {

// One shader object: its stage and its files, found (absolute or as the ShaderSource found
// them). The last file is the stage's own; earlier ones are inlined before it (the line kit's
// definitions before a hook).
struct ShaderStage {
    GLenum stage = 0;  // GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
    std::vector<std::string> files;
    // The stage a file's extension names: .vert .geom .frag .comp .tesc .tese. ShaderError otherwise.
    static GLenum of_extension(const std::string& file);
};

class ShaderProgram {
public:
    ShaderProgram() = default;
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;
    ShaderProgram(ShaderProgram&& o) noexcept;
    ShaderProgram& operator=(ShaderProgram&& o) noexcept;
    ~ShaderProgram();

    // A program of the given shader objects; `source` finds what their files #include.
    static ShaderProgram build(const std::vector<ShaderStage>& stages, const ShaderSource& source,
                               const std::vector<std::string>& defines = {});
    // A program of shader file names on `source`'s path, each its own object of the stage its
    // extension names.
    static ShaderProgram from_files(const std::vector<std::string>& names, const ShaderSource& source,
                                    const std::vector<std::string>& defines = {});
    static ShaderProgram from_files(const std::vector<std::string>& names, const std::vector<std::string>& dirs,
                                    const std::vector<std::string>& defines = {}) {
        return from_files(names, ShaderSource(dirs), defines);
    }

    GLuint id() const { return id_; }
    void use() const { glUseProgram(id_); }
    // A compute program's work group size (its layout(local_size_*)); 0 for any other program.
    glm::ivec3 local_size() const { return local_size_; }

    // What the linked program has, read back from GL (active uniforms outside blocks).
    struct Uniform {
        std::string name;  // "u_x"; arrays without "[0]"
        GLenum type = 0;   // GL_FLOAT, GL_FLOAT_VEC3, GL_SAMPLER_2D, GL_UNSIGNED_INT_IMAGE_2D, ...
        GLint size = 1;    // array length
        GLint location = -1;
        bool opaque = false;  // a sampler or an image: it has a unit
        bool image = false;
        int unit = -1;        // samplers: texture unit; images: image unit
    };
    const std::vector<Uniform>& uniforms() const { return uniforms_; }
    // Active uniform blocks, given binding points 0, 1, ... in GL's order (a layout(binding) in the
    // source is replaced, as for units): bind a block's buffer at block_binding(name).
    struct Block {
        std::string name;  // the block's name, "LineKit"
        int binding = -1;
    };
    const std::vector<Block>& uniform_blocks() const { return blocks_; }
    // The binding point of uniform block `name`, or -1 when the program does not use it.
    int block_binding(const std::string& name) const;
    const Uniform* uniform(const std::string& name) const;  // nullptr if not active
    // Gives the sampler or image `name` a unit (glProgramUniform1i; an array its elements units
    // `unit`, `unit`+1, ...). Units start as 0, 1, 2, ... over the opaque uniforms in GL's order,
    // samplers and images each in their own range; a pass's context renumbers them per pass.
    void set_unit(const std::string& name, int unit);
    // Binds a texture to the unit of sampler `name` (no-op when the sampler is optimised away).
    // Throws naming the program when the program declares no such sampler (a typo).
    void bind_texture(const std::string& name, GLuint texture) const;
    // Binds level `level` of a texture to the unit of image `name` with `format` (e.g. GL_R32UI).
    void bind_image(const std::string& name, GLuint texture, GLenum format, GLenum access = GL_READ_WRITE,
                    int level = 0) const;
    // Cached; -1 if declared but optimised away. A name no source of the program declares
    // (a typo: "u_tial") throws ShaderError naming the program's files and the uniform.
    GLint loc(const std::string& uniform) const;
    bool declares(const std::string& uniform) const;
    void set(const std::string& n, int v) const;
    void set(const std::string& n, float v) const;
    void set(const std::string& n, glm::vec2 v) const;
    void set(const std::string& n, glm::vec3 v) const;
    void set(const std::string& n, glm::vec4 v) const;
    void set(const std::string& n, glm::ivec2 v) const;
    void set(const std::string& n, glm::ivec4 v) const;
    void set(const std::string& n, const glm::mat4& v) const;

private:
    void reflect();
    const Uniform& opaque_uniform(const std::string& name) const;
    GLuint id_ = 0;
    std::vector<Uniform> uniforms_;
    std::vector<Block> blocks_;
    mutable std::map<std::string, GLint> locs_;
    std::set<std::string> declared_;  // uniform names found in the expanded sources
    std::string files_;               // "a.vert, b.geom, c.frag", for messages
    glm::ivec3 local_size_{0};
};

// A pass parameter used as an exponent, as a #define for shaders/pow_whole.glsl: "NAME n" when the
// value is a whole number in [1, 2047] (x^n by products, the program is rebuilt when it changes),
// nothing otherwise (the shader falls back to pow()).
inline std::vector<std::string> whole_exponent(const std::string& name, float value) {
    const float n = std::round(value);
    if (n == value && n >= 1.0f && n <= 2047.0f) return {name + " " + std::to_string(int(n))};
    return {};
}

}  // namespace pathlet
