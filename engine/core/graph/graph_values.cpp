// Variables and parameter values: "$var" substitution, type compatibility, coercion.
#include "graph_internal.hpp"

namespace pathlet::graph_detail {

const VariableDecl* find_variable(const GraphFile& g, const std::string& name) {
    for (const auto& v : g.variables)
        if (v.name == name) return &v;
    return nullptr;
}

std::vector<std::string> variable_names(const GraphFile& g) {
    std::vector<std::string> v;
    for (const auto& var : g.variables) v.push_back(var.name);
    return v;
}

bool is_variable_ref(const json& v) {
    return v.is_string() && v.get<std::string>().size() > 1 && v.get<std::string>()[0] == '$';
}

namespace {

// A variable may feed a parameter of the same type, an int a float, a string/enum an enum or
// string (the value is then checked against the choices), a vec3 a colour and back.
bool compatible(ParamType var, ParamType param) {
    auto textual = [](ParamType t) { return t == ParamType::String || t == ParamType::Enum; };
    auto vector = [](ParamType t) { return t == ParamType::Vec3 || t == ParamType::Color; };
    return var == param || (var == ParamType::Int && param == ParamType::Float) || (textual(var) && textual(param)) ||
           (vector(var) && vector(param));
}

// "$name" -> the variable, or an error.
const VariableDecl* lookup(const GraphFile& g, const json& ref, std::string& err) {
    const std::string name = ref.get<std::string>().substr(1);
    const VariableDecl* v = find_variable(g, name);
    if (!v) err = "unknown variable '$" + name + "'" + did_you_mean(name, variable_names(g), "$");
    return v;
}

}  // namespace

std::string resolve_param(const GraphFile& g, const ParamDecl& d, const json& written, json& out) {
    if (!is_variable_ref(written)) {
        std::string err = d.coerce(written, out);
        return err.empty() ? "" : "parameter '" + d.name + "' " + err;
    }
    std::string err;
    const VariableDecl* v = lookup(g, written, err);
    if (!v) return err;
    if (v->value.is_null()) {  // its declaration is wrong, reported there: the parameter's default meanwhile
        out = d.def;
        return "";
    }
    if (!compatible(v->decl.type, d.type))
        return "variable '$" + v->name + "' is " + to_string(v->decl.type) + " but parameter '" + d.name + "' is " +
               to_string(d.type);
    err = d.coerce(v->value, out);
    return err.empty() ? "" : "parameter '" + d.name + "' (from $" + v->name + " = " + v->value.dump() + ") " + err;
}

std::string resolve_enabled(const GraphFile& g, const json& enabled, bool& out) {
    if (enabled.is_boolean()) {
        out = enabled.get<bool>();
        return "";
    }
    if (!is_variable_ref(enabled)) return "enabled must be true, false or \"$variable\", got " + enabled.dump();
    std::string err;
    const VariableDecl* v = lookup(g, enabled, err);
    if (!v) return err;
    if (v->value.is_null()) return out = true, "";  // a wrong declaration, reported there
    if (v->decl.type != ParamType::Bool)
        return "enabled needs a bool variable, but '$" + v->name + "' is " + to_string(v->decl.type);
    out = v->value.get<bool>();
    return "";
}

}  // namespace pathlet::graph_detail
