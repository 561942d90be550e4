#include <pathlet/hook.hpp>

namespace pathlet {

namespace {
// LINE_WIDTH_HOOKED: line_quad.geom splits a segment where a width hook changes the width.
constexpr HookRoleInfo kRoles[] = {
    {HookRole::color, "color", "colour", "color_hook", "line_color_hook", "vec4 line_color_hook(vec4 rgba, LinePoint p)",
     GL_FRAGMENT_SHADER, ""},
    {HookRole::width, "width", "width", "width_hook", "line_width_hook", "float line_width_hook(LinePoint p)",
     GL_GEOMETRY_SHADER, "LINE_WIDTH_HOOKED"},
};
}  // namespace

const HookRoleInfo& hook_role(HookRole role) { return kRoles[role == HookRole::color ? 0 : 1]; }

const HookRoleInfo* hook_role_of_param(const std::string& param) {
    for (const auto& r : kRoles)
        if (param == r.param) return &r;
    return nullptr;
}

}  // namespace pathlet
