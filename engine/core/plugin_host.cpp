#include "plugin_host.hpp"

#include "plugin_elf.hpp"
#include "plugin_trust.hpp"

#include <pathlet/plugin.hpp>

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace pathlet {

std::string engine_library_dir() {
    Dl_info info{};
    // Canonical: a RUNPATH like $ORIGIN/../../.. (the installed Python module's) gives a name
    // with "..", whose lexical parent is not the folder above.
    std::error_code ec;
    if (dladdr(reinterpret_cast<void*>(&engine_library_dir), &info) && info.dli_fname)
        return fs::weakly_canonical(fs::absolute(fs::path(info.dli_fname)), ec).parent_path().string();
    return ".";
}

std::string engine_share_dir() {
    if (const char* e = std::getenv("PATHLET_SHARE_DIR")) return e;
    fs::path beside = fs::path(engine_library_dir()).parent_path() / "share" / "pathlet";
    if (fs::exists(beside / "shaders")) return beside.string();
    fs::path installed = PATHLET_INSTALL_SHARE_DIR;
    if (fs::exists(installed / "shaders")) return installed.string();
    return PATHLET_SOURCE_DIR;  // running from an unusual place inside the build tree
}

std::string share_dir() { return engine_share_dir(); }  // the SDK's name for it (pass.hpp)

std::vector<std::string> PluginHost::search_path(const std::vector<std::string>& extra_dirs) {
    std::vector<std::string> dirs = extra_dirs;
    if (const char* env = std::getenv("PATHLET_PLUGIN_PATH")) {
        std::stringstream s(env);
        std::string d;
        while (std::getline(s, d, ':'))
            if (!d.empty()) dirs.push_back(d);
    }
    dirs.push_back((fs::path(engine_library_dir()) / "pathlet" / "passes").string());
    // Remove duplicates, keep order.
    std::vector<std::string> out;
    std::set<std::string> seen;
    for (const auto& d : dirs) {
        std::error_code ec;
        std::string key = fs::weakly_canonical(d, ec).string();
        if (key.empty()) key = d;
        if (seen.insert(key).second) out.push_back(key);  // canonical: messages show clean paths
    }
    return out;
}

namespace {
// Collects types first so a plugin that fails half-way registers nothing.
struct CollectingSink : PassSink {
    std::vector<PassTypeInfo> types;
    void add(PassTypeInfo info) override { types.push_back(std::move(info)); }
};
}  // namespace

PluginHost::FolderScan PluginHost::scan_dir(const std::string& dir) {
    FolderScan scan;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (it->path().extension() != ".so") continue;
        (name.rfind("pathlet_", 0) == 0 && name.size() > 11 ? scan.plugins : scan.others).push_back(it->path().string());
    }
    std::sort(scan.plugins.begin(), scan.plugins.end());
    std::sort(scan.others.begin(), scan.others.end());
    return scan;
}


std::string PluginHost::folder_problem(const std::string& dir) {
    struct stat st {};
    if (::stat(dir.c_str(), &st) != 0) return "";  // nothing there, nothing loaded
    return write_access_problem(dir, st, "plugin folder", false);
}

void PluginHost::load_file(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw PluginError(path + ": file not found");
    if (!S_ISREG(st.st_mode)) throw PluginError(path + ": not a regular file; never opened");
    if (std::string why = write_access_problem(path, st, "plugin file", false); !why.empty())
        throw PluginError(why + "; never opened");
    PluginSymbols sym;
    try {
        sym = read_plugin_symbols_of_file(path);
    } catch (const ElfError& e) {
        throw PluginError(path + ": not a Pathlet plugin (" + e.what() + "); never opened");
    }
    if (!sym.entry)
        throw PluginError(path + ": not a Pathlet plugin (no " PATHLET_PLUGIN_ENTRY
                                 " entry point; build it with pathlet_add_pass() and PATHLET_PLUGIN()); never opened");
    if (sym.sdk != PATHLET_SDK_FINGERPRINT)
        throw PluginError(path + ": built against " +
                          (sym.sdk.empty() ? std::string("an older SDK (no SDK fingerprint)")
                                           : "another SDK (fingerprint " + sym.sdk + ")") +
                          ", this engine's SDK is " PATHLET_SDK_FINGERPRINT ": rebuild against this SDK; never opened");
    // RTLD_NOW: an unresolved symbol fails here, cleanly, instead of killing the process at
    // its first call. RTLD_LOCAL: plugins cannot clash with each other's symbols.
    void* h = dlopen(fs::absolute(path).c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char* e = dlerror();
        throw PluginError(path + ": cannot load: " + (e ? e : "unknown dlopen error"));
    }
    using Entry = const PluginDescriptor* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(h, PATHLET_PLUGIN_ENTRY));
    if (!entry)
        throw PluginError(path + ": not a Pathlet plugin (no " PATHLET_PLUGIN_ENTRY
                                 " entry point; build it with pathlet_add_pass() and PATHLET_PLUGIN())");
    const PluginDescriptor* d = nullptr;
    try {
        d = entry();
    } catch (...) {
        throw PluginError(path + ": its entry point threw an exception");
    }
    if (!d) throw PluginError(path + ": entry point returned no descriptor");
    if (d->abi_version != PATHLET_PLUGIN_ABI_VERSION)
        throw PluginError(path + ": plugin ABI version " + std::to_string(d->abi_version) +
                          " does not match the engine's ABI version " + std::to_string(PATHLET_PLUGIN_ABI_VERSION) +
                          "; rebuild the plugin against this Pathlet SDK");
    if (d->struct_size != sizeof(PluginDescriptor))
        throw PluginError(path + ": plugin descriptor size mismatch; rebuild the plugin against this Pathlet SDK");
    if (!d->fingerprint || std::strcmp(d->fingerprint, PATHLET_BUILD_FINGERPRINT_STR) != 0)
        throw PluginError(path + ": built with a different compiler/standard library (" +
                          (d->fingerprint ? d->fingerprint : "none") + ", engine: " PATHLET_BUILD_FINGERPRINT_STR
                          "); rebuild the plugin with the engine's toolchain");
    if (!d->register_passes) throw PluginError(path + ": descriptor has no register function");
    CollectingSink sink;
    try {
        d->register_passes(&sink);
    } catch (const std::exception& e) {
        throw PluginError(path + ": registering its pass types threw: " + e.what());
    } catch (...) {
        throw PluginError(path + ": registering its pass types threw a non-standard exception");
    }
    if (sink.types.empty()) throw PluginError(path + ": plugin registered no pass types");
    // Check all names before adding any, so a duplicate leaves the registry unchanged.
    std::set<std::string> names;
    for (auto& t : sink.types) {
        if (!t.create) throw PluginError(path + ": pass type '" + t.type + "' has no factory");
        if (!names.insert(t.type).second)
            throw PluginError(path + ": registers pass type '" + t.type + "' twice");
        if (const PassTypeInfo* prev = registry_.find(t.type))
            throw PluginError(path + ": pass type '" + t.type + "' is already registered by " + prev->plugin_file +
                              "; rename one of them or remove one plugin from the search path");
    }
    Loaded l{path, d->name ? d->name : "", {}};
    for (auto& t : sink.types) {
        t.plugin_file = path;
        l.types.push_back(t.type);
        registry_.add(std::move(t));
    }
    loaded_.push_back(std::move(l));
    // The handle is never closed: pass objects and their vtables live in the plugin.
}

void PluginHost::load_dirs(const std::vector<std::string>& dirs) {
    for (const auto& dir : dirs) {
        registry_.add_searched_dir(dir);
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) continue;
        const FolderScan scan = scan_dir(dir);
        if (scan.plugins.empty() && scan.others.empty()) continue;
        if (std::string why = folder_problem(dir); !why.empty()) {
            problems_.push_back(why + "; nothing loaded from it");
            continue;
        }
        for (const auto& f : scan.others)
            notes_.push_back(f + ": skipped, not named like a Pathlet plugin (pathlet_<name>.so, as pathlet_add_pass() "
                                 "builds them); never opened");
        for (const auto& f : scan.plugins) {
            try {
                load_file(f);
            } catch (const PluginError& e) {
                problems_.push_back(e.what());
            }
        }
    }
}

}  // namespace pathlet
