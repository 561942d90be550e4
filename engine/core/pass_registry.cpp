#include "pass_registry.hpp"

#include <algorithm>

#include <stdexcept>

namespace pathlet {

void PassRegistry::add(PassTypeInfo info) {
    auto it = types_.find(info.type);
    if (it != types_.end())
        throw std::runtime_error(info.plugin_file + ": pass type '" + info.type + "' is already registered by " +
                                 (it->second.plugin_file.empty() ? std::string("the engine") : it->second.plugin_file) +
                                 "; rename one of them or remove one plugin from the search path");
    if (!info.gpu_wait_when.empty()) {
        const ParamDecl* when = info.param(info.gpu_wait_when);
        if (!when || when->type != ParamType::Bool)
            throw std::runtime_error(info.plugin_file + ": pass type '" + info.type + "' declares that it waits for the GPU with '" +
                                     info.gpu_wait_when + "', which is not one of its bool parameters");
    }
    std::string name = info.type;
    types_.emplace(std::move(name), std::move(info));
}

const PassTypeInfo* PassRegistry::find(const std::string& type) const {
    auto it = types_.find(type);
    return it == types_.end() ? nullptr : &it->second;
}

std::vector<const PassTypeInfo*> PassRegistry::all() const {
    std::vector<const PassTypeInfo*> v;
    for (const auto& [k, t] : types_) v.push_back(&t);
    return v;
}

std::vector<std::string> PassRegistry::names() const {
    std::vector<std::string> v;
    for (const auto& [k, t] : types_) v.push_back(k);
    return v;
}

void PassRegistry::add_searched_dir(const std::string& dir) {
    if (std::find(searched_.begin(), searched_.end(), dir) == searched_.end()) searched_.push_back(dir);
}

}  // namespace pathlet
