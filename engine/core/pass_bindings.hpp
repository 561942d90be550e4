// How a pass's programs are bound by declaration, said in one place for the executor and for
// `pathlet validate`'s hook compile (pathlet/pass.hpp, ARCHITECTURE.md):
//   buffer pins (and internal buffers)  storage binding points 0, 1, ... in declaration order,
//                                       known to every program of the pass as <PIN>_BINDING
//   samplers and images                 texture and image units per pass, each kind from 0; a
//                                       texture pin's u_<pin> has one unit in every program
//   parameters                          u_<param> (pixel lengths times the pixel scale)
// Units and binding points stay within the context's limits (pathlet/gl_limits.hpp).
#pragma once

#include <pathlet/pass.hpp>
#include <pathlet/shader.hpp>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace pathlet {

class PassBindings {
public:
    PassBindings() = default;
    // Buffer binding points from the type's declaration. Throws std::runtime_error when the
    // context has fewer storage-buffer binding points than the type has buffer pins.
    explicit PassBindings(const PassTypeInfo& type, bool check_limits = false);

    // Storage binding point of buffer pin `pin`, -1 when it is not one.
    int buffer(const std::string& pin) const;
    const std::map<std::string, int>& buffers() const { return buffers_; }
    // "NODES_BINDING 0", ...: every program of the pass has them.
    std::vector<std::string> defines() const;

    // Gives a new program's samplers and images their units: a texture pin's the pin's (taken
    // by the first program that uses it), any other the next free one. Throws std::runtime_error
    // naming the uniform and the limit when the pass needs more than the context has.
    void assign_units(ShaderProgram& prog, const PassTypeInfo& type);
    // Texture pins the pass's programs read as samplers or images, with their units.
    const std::map<std::string, int>& sampler_pins() const { return sampler_pins_; }
    const std::map<std::string, int>& image_pins() const { return image_pins_; }
    int samplers() const { return samplers_; }  // units taken, each kind
    int images() const { return images_; }

    // Sets u_<param> of `prog` to the pass's parameter values. ShaderError when a uniform of that
    // name has a type the parameter cannot take.
    static void bind_params(const ShaderProgram& prog, const PassTypeInfo& type, const Params& params, float pixel_scale);

private:
    int take(bool image, int count, const std::string& uniform);
    std::map<std::string, int> buffers_;
    std::map<std::string, int> sampler_pins_, image_pins_;
    int samplers_ = 0, images_ = 0;
};

}  // namespace pathlet
