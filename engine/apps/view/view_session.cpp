#include "view/view_session.hpp"

#include "gl_context.hpp"
#include "view/file_watch.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

namespace pathlet::view {

ViewSession::ViewSession(Runtime& rt, const GpuScene& scene, glm::ivec2 size, std::string graph_path,
                         const std::vector<std::string>& sets)
    : rt_(rt), scene_(scene), size_(size), path_(std::move(graph_path)) {
    for (const auto& s : sets) {
        const size_t eq = s.find('=');
        overrides_.emplace_back(s.substr(0, eq), eq == std::string::npos ? "" : s.substr(eq + 1));
    }
    cur_ = build(this->sets());  // the first graph must work: its errors go to the command line
}

ViewSession::~ViewSession() = default;

std::vector<std::string> ViewSession::sets() const {
    std::vector<std::string> out;
    for (const auto& [n, v] : overrides_) out.push_back(n + "=" + v);
    return out;
}

std::unique_ptr<ViewSession::Built> ViewSession::build(const std::vector<std::string>& sets) const {
    auto b = std::make_unique<Built>();
    b->g = rt_.load_graph(path_, sets);
    for (const auto& n : b->g.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
    b->cg = compile_graph(b->g, rt_.registry, size_);
    if (b->cg.outputs.empty()) throw std::runtime_error(path_ + ": the graph has no output to show");
    b->prof = std::make_unique<Profiler>();
    b->prof->init(TimingBackend::Auto, rt_.gl->renderer());
    b->prof->set_warmup_frames(0);
    b->exec = std::make_unique<Executor>(*rt_.gl, b->cg, scene_, b->prof.get());
    b->exec->setup();
    return b;
}

bool ViewSession::rebuild() {
    try {
        std::unique_ptr<Built> next = build(sets());
        cur_->prof->release_gl();
        cur_ = std::move(next);
        error_.clear();
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

bool ViewSession::switch_graph(const std::string& path) {
    const std::string old_path = path_;
    auto old_overrides = overrides_;
    path_ = path;
    overrides_.clear();
    if (rebuild()) return true;
    path_ = old_path;  // keep showing (and watching) the graph that works
    overrides_ = std::move(old_overrides);
    error_ = "could not switch to " + path + ":\n" + error_;
    return false;
}

bool ViewSession::same_structure(const CompiledGraph& a, const CompiledGraph& b) const {
    if (a.passes.size() != b.passes.size() || a.resources.size() != b.resources.size()) return false;
    // Types by name and parameter list: a pass's hook may bring parameters (each compile makes
    // its own copy of such a type); another hook with the same parameters is a parameter change.
    auto params_of = [](const PassTypeInfo& t) {
        std::vector<std::string> n;
        for (const auto& p : t.params) n.push_back(p.name);
        return n;
    };
    for (size_t i = 0; i < a.passes.size(); ++i)
        if (a.passes[i].name != b.passes[i].name || a.passes[i].type->type != b.passes[i].type->type ||
            params_of(*a.passes[i].type) != params_of(*b.passes[i].type))
            return false;
    return plan_to_text(a) == plan_to_text(b);  // order, formats, sizes, lifetimes, pooling
}

bool ViewSession::set(const std::string& name, const std::string& value) {
    auto overrides = overrides_;
    auto it = std::find_if(overrides.begin(), overrides.end(), [&](const auto& o) { return o.first == name; });
    if (it != overrides.end()) it->second = value;
    else overrides.emplace_back(name, value);
    std::vector<std::string> s;
    for (const auto& [n, v] : overrides) s.push_back(n + "=" + v);
    try {
        GraphFile g = rt_.load_graph(path_, s);
        CompiledGraph cg = compile_graph(g, rt_.registry, size_);
        if (!same_structure(cg, cur_->cg)) {  // e.g. a variable that switches a pass's pins
            auto saved = overrides_;
            overrides_ = overrides;
            if (rebuild()) return true;
            overrides_ = saved;
            return false;
        }
        // Same passes and resources: only the passes whose parameters changed set up again.
        for (size_t i = 0; i < cg.passes.size(); ++i) {
            if (cg.passes[i].params == cur_->cg.passes[i].params) continue;
            json old = cur_->cg.passes[i].params;
            cur_->cg.passes[i].params = cg.passes[i].params;
            try {
                cur_->exec->reparam(i);
            } catch (...) {
                cur_->cg.passes[i].params = old;
                throw;
            }
        }
        cur_->g = std::move(g);
        overrides_ = std::move(overrides);
        error_.clear();
        return true;
    } catch (const std::exception& e) {
        error_ = e.what();
        return false;
    }
}

json ViewSession::value(const std::string& name) const {
    const size_t dot = name.find('.');
    if (dot == std::string::npos) {
        for (const auto& v : cur_->g.variables)
            if (v.name == name) return v.value;
        return nullptr;
    }
    for (const auto& p : cur_->cg.passes)
        if (p.name == name.substr(0, dot) && p.params.contains(name.substr(dot + 1)))
            return p.params.at(name.substr(dot + 1));
    return nullptr;
}

std::vector<std::string> ViewSession::watched_files() const {
    std::set<std::string> dirs, hooks;
    for (size_t i = 0; i < cur_->cg.passes.size(); ++i) {
        const ShaderSource& s = cur_->exec->shaders(i);
        dirs.insert(s.dirs().begin(), s.dirs().end());
        for (const auto& [role, file] : s.hooks()) hooks.insert(file);
    }
    return graph_and_shader_files(path_, {dirs.begin(), dirs.end()}, {hooks.begin(), hooks.end()});
}

}  // namespace pathlet::view
