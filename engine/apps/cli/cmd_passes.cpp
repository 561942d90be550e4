// pathlet passes [--describe TYPE]: what pass types the plugin search path provides.
#include "commands.hpp"
#include "common_options.hpp"
#include "graph/graph_model.hpp"
#include "graph/hook_params.hpp"
#include "runtime.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <cstdio>
#include <filesystem>

namespace pathlet::cli {
namespace {

// A type as a graph would see it with its default hooks: their @param uniforms included.
std::shared_ptr<const PassTypeInfo> with_default_hooks(const PassTypeInfo& t) {
    try {
        return instance_type_with(t);
    } catch (const HookError& e) {
        std::fprintf(stderr, "warning: %s: default hook: %s\n", t.type.c_str(), e.what());
        return {&t, [](const PassTypeInfo*) {}};
    }
}

// The type with the hooks --set names (color_hook=FILE: a file of yours, relative to the current
// folder, or a name on the shader path): the parameters those hooks declare, with their docs.
std::shared_ptr<const PassTypeInfo> with_hooks(const PassTypeInfo& t, const std::vector<std::string>& sets) {
    std::map<HookRole, std::string> names;
    std::set<std::string> chosen;  // the user's files, found by their paths
    for (const auto& set : sets) {
        const auto eq = set.find('=');
        const std::string name = set.substr(0, eq), value = eq == std::string::npos ? "" : set.substr(eq + 1);
        const ParamDecl* d = t.param(name);
        std::vector<std::string> hooks;
        for (const auto& p : t.params)
            if (p.hook) hooks.push_back(p.name);
        if (eq == std::string::npos || !d || !d->hook)
            throw UsageError("--set " + set + ": --describe takes a hook file, " +
                             (hooks.empty() ? std::string("and '") + t.type + "' has no hook parameters"
                                            : "as " + text::join(hooks, "=FILE or ") + "=FILE" +
                                                  text::did_you_mean(name, hooks)));
        std::error_code ec;
        std::string file = value;
        if (value.find('/') != std::string::npos || std::filesystem::is_regular_file(value, ec)) {
            file = std::filesystem::absolute(value).lexically_normal().string();
            if (!std::filesystem::is_regular_file(file, ec)) throw InputError("--set " + set + ": no hook file " + file);
            chosen.insert(file);
        }
        names[*d->hook] = file;
    }
    try {
        return instance_type_with(t, names, chosen);
    } catch (const HookError& e) {
        throw InputError(std::string(e.what()));
    }
}

int run(const std::vector<std::string>& argv) {
    Args a("passes",
           "Lists the pass types found on the plugin search path, with the file each comes from.\n"
           "\n"
           "Where plugins come from, and which are trusted (loading a plugin runs its code):\n"
           "  - the search path: --plugin-dir folders, PATHLET_PLUGIN_PATH, the built-in folder. You chose\n"
           "    these, so they are trusted.\n"
           "  - \"plugin_dirs\" in a graph file: loaded only when trusted ('pathlet trust DIR' lists it in\n"
           "    ~/.config/pathlet/trusted-plugin-dirs, honouring XDG_CONFIG_HOME) or for one run with\n"
           "    --trust-graph-plugins. Otherwise render, bench, view and graph stop before loading\n"
           "    anything and print the command that trusts the folder; validate reports the pass types\n"
           "    the folder may provide without opening it.\n"
           "Before any file is opened: it must be named pathlet_<name>.so (as pathlet_add_pass() builds it;\n"
           "other files are skipped with a note), neither it nor its folder may be world-writable or\n"
           "another user's (root's is fine), and its ELF symbol table, read without loading it, must hold\n"
           "the pathlet_plugin_v1 entry point and this SDK's fingerprint (else: rebuild against this SDK).\n"
           "\n"
           "A line pass's parameters include those its hook files declare (color_hook, width_hook):\n"
           "--describe shows them for the default hooks.");
    std::string describe;
    std::vector<std::string> sets;
    bool as_json = false, markdown = false;
    PluginOptions plugins;
    a.option("describe", describe, "TYPE", "print the parameters and pins of one pass type")
        .multi("set", sets, "HOOK=FILE",
               "with --describe: the pass with this hook file (color_hook=my_fade.glsl, width_hook=...): the "
               "parameters its @param uniforms declare, with type, default, range and doc");
    plugins.declare(a, /*graph_files=*/false);
    a.flag("json", as_json, "print the declarations as JSON (for tools and docs)")
        .flag("markdown", markdown, "with --describe: the parameter and pin tables as Markdown, as pass READMEs embed "
                                    "them; alone: the index of every pass type, as passes/README.md embeds it "
                                    "(scripts/update-pass-docs.sh)")
        .example("pathlet passes", "list all pass types")
        .example("pathlet passes --describe lineao", "parameters (type, default, range, doc) and pins of lineao")
        .example("pathlet passes --describe fill_list --set color_hook=my_fade.glsl", "... with your hook's parameters");
    if (!a.parse(argv)) return 0;
    if (!sets.empty() && describe.empty()) throw UsageError("--set needs --describe TYPE");
    Runtime rt;
    plugins.load(rt);
    if (!describe.empty()) {
        const PassTypeInfo* t = rt.registry.find(describe);
        if (!t) {
            std::fprintf(stderr, "error: no pass type '%s'%s; 'pathlet passes' lists them%s\n", describe.c_str(),
                         text::did_you_mean(describe, rt.registry.names()).c_str(), rt.plugin_problems_note().c_str());
            return 2;
        }
        const auto inst = sets.empty() ? with_default_hooks(*t) : with_hooks(*t, sets);
        std::fputs((markdown ? inst->markdown() : inst->describe()).c_str(), stdout);
        return 0;
    }
    if (markdown) {
        std::fputs(index_markdown(rt.registry.all()).c_str(), stdout);
        return rt.host.problems().empty() ? 0 : 1;
    }
    if (as_json) {
        json out = json::array();
        for (const auto* reg_type : rt.registry.all()) {
            const auto inst = with_default_hooks(*reg_type);
            const PassTypeInfo* t = inst.get();
            json pt = {{"type", t->type}, {"doc", t->doc}, {"file", t->plugin_file}, {"params", json::array()}, {"pins", json::array()}};
            for (const auto& p : t->params)
                pt["params"].push_back({{"name", p.name}, {"type", to_string(p.type)}, {"default", p.def}, {"doc", p.doc}});
            for (const auto& p : t->pins)
                pt["pins"].push_back({{"name", p.name}, {"dir", direction_name(p)},
                                      {"kind", p.kind == PinKind::Texture ? "texture" : "buffer"}, {"format", p.format},
                                      {"optional", p.optional}, {"doc", p.doc}});
            out.push_back(pt);
        }
        std::printf("%s\n", out.dump(2).c_str());
        return rt.host.problems().empty() ? 0 : 1;
    }
    std::printf("%-16s %-60s %s\n", "TYPE", "WHAT IT DOES", "FILE");
    for (const auto* t : rt.registry.all()) {
        std::string doc = t->doc.size() > 58 ? t->doc.substr(0, 57) + "…" : t->doc;
        std::printf("%-16s %-60s %s\n", t->type.c_str(), doc.c_str(), t->plugin_file.c_str());
    }
    if (rt.registry.all().empty()) {
        std::printf("(no pass types found) searched:\n");
        for (const auto& d : PluginHost::search_path(plugins.dirs)) std::printf("  %s\n", d.c_str());
    }
    for (const auto& n : rt.host.notes()) std::fprintf(stderr, "note: %s\n", n.c_str());
    for (const auto& p : rt.host.problems()) std::fprintf(stderr, "error: %s\n", p.c_str());
    return rt.host.problems().empty() ? 0 : 1;
}

PATHLET_COMMAND("passes", "list pass plugins, or describe one (--describe TYPE)", run);

}  // namespace
}  // namespace pathlet::cli
