// GLSL programs loaded from files on the shader search path, with `#include "file"`
// resolved there too. Each source file gets a number in #line directives, so compile
// errors are reported as "<file>:<line>: <message>" (ShaderError).
#pragma once

#include <pathlet/gl.hpp>

#include <glm/glm.hpp>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

struct ShaderError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class ShaderProgram {
public:
    ShaderProgram() = default;
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;
    ShaderProgram(ShaderProgram&& o) noexcept;
    ShaderProgram& operator=(ShaderProgram&& o) noexcept;
    ~ShaderProgram();

    // Stage by extension: .vert .geom .frag .comp. `dirs` are searched in order.
    static ShaderProgram from_files(const std::vector<std::string>& files, const std::vector<std::string>& dirs,
                                    const std::vector<std::string>& defines = {});

    GLuint id() const { return id_; }
    void use() const { glUseProgram(id_); }
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
    void set(const std::string& n, const glm::mat4& v) const;

private:
    GLuint id_ = 0;
    mutable std::map<std::string, GLint> locs_;
    std::set<std::string> declared_;  // uniform names found in the expanded sources
    std::string files_;               // "a.vert, b.geom, c.frag", for messages
};

// A pass parameter used as an exponent, as a #define for shaders/pow_whole.glsl: "NAME n" when the
// value is a whole number in [1, 2047] (x^n by products, the program is rebuilt when it changes),
// nothing otherwise (the shader falls back to pow()).
inline std::vector<std::string> whole_exponent(const std::string& name, float value) {
    const float n = std::round(value);
    if (n == value && n >= 1.0f && n <= 2047.0f) return {name + " " + std::to_string(int(n))};
    return {};
}

// Finds a file on the search path; throws ShaderError listing the directories searched. `name`
// is a file name: one with a '/' (absolute or relative) or ".." is refused.
std::string find_shader_file(const std::string& name, const std::vector<std::string>& dirs);

}  // namespace pathlet
