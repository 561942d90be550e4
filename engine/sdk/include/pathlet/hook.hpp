// Hooks: the small GLSL functions a line pass plugs into the line kit's stages (a fade
// strategy is one). Their roles, declared once: the pass parameter that names the file, the
// function the file defines and the stage it is compiled as. Everything that reads, checks,
// compiles or documents a hook takes these from here.
#pragma once

#include <pathlet/gl.hpp>

#include <string>

namespace pathlet {

enum class HookRole { color, width };

struct HookRoleInfo {
    HookRole role;
    const char* name;       // "color", "width"
    const char* noun;       // "colour", "width": how messages say it
    const char* param;      // the pass parameter naming the file: "color_hook"
    const char* function;   // "line_color_hook"
    const char* signature;  // "vec4 line_color_hook(vec4 rgba, LinePoint p)"
    GLenum stage;           // what the file is compiled as
    const char* defines;    // a define the pass's programs get while the hook is in place ("" none)
};

inline constexpr HookRole kHookRoles[] = {HookRole::color, HookRole::width};

const HookRoleInfo& hook_role(HookRole role);
// The role whose file parameter is `param` ("color_hook"), or nullptr for any other parameter.
const HookRoleInfo* hook_role_of_param(const std::string& param);

}  // namespace pathlet
