// All pass types known to this process, by type name (filled by the plugin host).
#pragma once

#include <pathlet/pass.hpp>

#include <map>
#include <string>
#include <vector>

namespace pathlet {

class PassRegistry {
public:
    // Throws std::runtime_error on a duplicate type name, naming both files.
    void add(PassTypeInfo info);
    const PassTypeInfo* find(const std::string& type) const;
    std::vector<const PassTypeInfo*> all() const;  // sorted by type name
    std::vector<std::string> names() const;

    // Folders the plugin host searched, in order (for "unknown pass type" hints).
    void add_searched_dir(const std::string& dir);
    const std::vector<std::string>& searched_dirs() const { return searched_; }

private:
    std::map<std::string, PassTypeInfo> types_;
    std::vector<std::string> searched_;
};

}  // namespace pathlet
