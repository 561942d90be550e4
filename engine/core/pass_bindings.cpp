#include "pass_bindings.hpp"

#include <pathlet/gl_limits.hpp>

#include <cmath>
#include <stdexcept>

namespace pathlet {

PassBindings::PassBindings(const PassTypeInfo& type, bool check_limits) {
    for (const PinDecl& pin : type.pins)
        if (pin.kind == PinKind::Buffer) buffers_.emplace(pin.name, int(buffers_.size()));
    if (!check_limits) return;
    const GlLimits& limits = gl_limits();
    const int points = limits.get(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
    if (int(buffers_.size()) > points)
        throw std::runtime_error("its " + std::to_string(buffers_.size()) +
                                 " buffer pins need as many storage-buffer binding points; this context has " +
                                 std::to_string(points) + limits.source(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS));
}

int PassBindings::buffer(const std::string& pin) const {
    const auto it = buffers_.find(pin);
    return it == buffers_.end() ? -1 : it->second;
}

std::vector<std::string> PassBindings::defines() const {
    std::vector<std::string> out;
    for (const auto& [pin, point] : buffers_) out.push_back(binding_define(pin) + " " + std::to_string(point));
    return out;
}

// The next `count` sampler or image units of the pass, within the context's limits.
int PassBindings::take(bool image, int count, const std::string& uniform) {
    const GlLimits& limits = gl_limits();
    const GLenum limit = image ? GL_MAX_IMAGE_UNITS : GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS;
    int& next = image ? images_ : samplers_;
    const int first = next;
    next += std::max(count, 1);
    if (next > limits.get(limit))
        throw std::runtime_error(std::string("'") + uniform + "' needs " + (image ? "image" : "texture") + " unit " +
                                 std::to_string(next - 1) + " (" + std::to_string(next) + " " +
                                 (image ? "images" : "samplers") + " in the pass's programs); this context has " +
                                 std::to_string(limits.get(limit)) + (image ? " image units" : " texture units") +
                                 limits.source(limit));
    return first;
}

void PassBindings::assign_units(ShaderProgram& prog, const PassTypeInfo& type) {
    for (const auto& u : std::vector<ShaderProgram::Uniform>(prog.uniforms())) {
        if (!u.opaque) continue;
        const std::string pin = u.name.rfind("u_", 0) == 0 ? u.name.substr(2) : "";
        const PinDecl* decl = pin.empty() ? nullptr : type.pin(pin);
        const bool is_pin = decl && decl->kind == PinKind::Texture;
        std::map<std::string, int>& pins = u.image ? image_pins_ : sampler_pins_;
        int unit = 0;
        if (is_pin && pins.count(pin)) {
            unit = pins[pin];
        } else {
            unit = take(u.image, u.size, u.name);
            if (is_pin) pins[pin] = unit;
        }
        prog.set_unit(u.name, unit);
    }
}

namespace {
const char* glsl_type_name(GLenum t) {
    switch (t) {
        case GL_FLOAT: return "float";
        case GL_FLOAT_VEC2: return "vec2";
        case GL_FLOAT_VEC3: return "vec3";
        case GL_FLOAT_VEC4: return "vec4";
        case GL_INT: return "int";
        case GL_INT_VEC2: return "ivec2";
        case GL_UNSIGNED_INT: return "uint";
        case GL_BOOL: return "bool";
        case GL_FLOAT_MAT4: return "mat4";
        default: return "another type";
    }
}
}  // namespace

void PassBindings::bind_params(const ShaderProgram& prog, const PassTypeInfo& type, const Params& params,
                               float pixel_scale) {
    for (const ParamDecl& d : type.params) {
        if (d.type == ParamType::String) continue;
        const ShaderProgram::Uniform* u = prog.uniform("u_" + d.name);
        if (!u || u->opaque) continue;
        const json& v = params.raw().at(d.name);
        const GLuint id = prog.id();
        const float scale = d.pixels ? pixel_scale : 1.0f;
        bool fits = true;
        switch (d.type) {
            case ParamType::Bool:
                fits = u->type == GL_BOOL || u->type == GL_INT;
                if (fits) glProgramUniform1i(id, u->location, v.get<bool>() ? 1 : 0);
                break;
            case ParamType::Int: {
                const double x = v.get<double>() * scale;
                if (u->type == GL_INT || u->type == GL_BOOL) glProgramUniform1i(id, u->location, int(std::lround(x)));
                else if (u->type == GL_UNSIGNED_INT) glProgramUniform1ui(id, u->location, GLuint(std::llround(std::max(x, 0.0))));
                else if (u->type == GL_FLOAT) glProgramUniform1f(id, u->location, float(x));
                else fits = false;
                break;
            }
            case ParamType::Float:
                fits = u->type == GL_FLOAT;
                if (fits) glProgramUniform1f(id, u->location, float(v.get<double>() * scale));
                break;
            case ParamType::Enum:
                fits = u->type == GL_INT;
                if (fits) glProgramUniform1i(id, u->location, params.index(d.name));
                break;
            case ParamType::Vec3:
            case ParamType::Color:
                fits = u->type == GL_FLOAT_VEC3;
                if (fits) glProgramUniform3f(id, u->location, v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
                break;
            case ParamType::String: break;
        }
        if (!fits)
            throw ShaderError("uniform 'u_" + d.name + "' is " + glsl_type_name(u->type) + " in the program, but parameter '" +
                              d.name + "' is " + to_string(d.type) +
                              " (declared parameters reach u_<name>: rename the uniform or fix its type)");
    }
}

}  // namespace pathlet
