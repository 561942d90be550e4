#include "view/view_panels.hpp"

#include "view/panel_values.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

namespace pathlet::view {

std::string set_text(ParamType type, const json& v) {
    switch (type) {
        case ParamType::Bool: return v.get<bool>() ? "true" : "false";
        case ParamType::String:
        case ParamType::Enum: return v.get<std::string>();
        case ParamType::Color: {
            char buf[16];
            auto c = [&](int i) { return std::clamp(int(std::lround(v.at(i).get<double>() * 255.0)), 0, 255); };
            std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c(0), c(1), c(2));
            return buf;
        }
        default: return v.dump();  // numbers and [x,y,z]
    }
}

namespace {

void tooltip(const ParamDecl& d) {
    if (!ImGui::IsItemHovered()) return;
    std::string tip = d.doc;
    if (std::isfinite(d.min) || std::isfinite(d.max)) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "\nrange [%g, %g], default %s", d.min, d.max, d.def.dump().c_str());
        tip += buf;
    } else {
        tip += "\ndefault " + d.def.dump();
    }
    ImGui::SetTooltip("%s", tip.c_str());
}

// While a slider is dragged the widget shows its own value (kept in ImGui's storage); the
// change is applied once, when the drag ends: every change sets a pass up again.
struct Deferred {
    ImGuiStorage* st = ImGui::GetStateStorage();
    ImGuiID editing = ImGui::GetID("editing");
    bool active() const { return st->GetBool(editing, false); }
    static ImGuiID key(int k) { return ImGui::GetID(("v" + std::to_string(k)).c_str()); }
    float get(int k, float fallback) const { return active() ? st->GetFloat(key(k), fallback) : fallback; }
    // After the widget: true when an edit just finished.
    bool track(const float* v, int n) {
        if (ImGui::IsItemActive()) {
            st->SetBool(editing, true);
            for (int k = 0; k < n; ++k) st->SetFloat(key(k), v[k]);
        }
        if (ImGui::IsItemDeactivated()) st->SetBool(editing, false);
        return ImGui::IsItemDeactivatedAfterEdit();
    }
};

// The values in use (view/panel_values.hpp) from the passes' stats, kept between the
// profiler's windows of 30 frames.
InUse& in_use() {
    static InUse values;
    return values;
}
void update_in_use(ViewSession& session) {
    for (const auto& p : session.profiler().passes())
        for (const auto& [name, value] : p.stats) {
            in_use()[p.name + "." + name] = value;
            in_use()[name] = value;
        }
}

// One widget for one declared parameter; a finished change is queued as a --set.
void param_widget(const std::string& set_name, const std::string& label, const ParamDecl& d, const json& v,
                  PanelActions& out) {
    if (v.is_null()) return;
    ImGui::PushID(set_name.c_str());
    const bool bounded = std::isfinite(d.min) && std::isfinite(d.max) && d.max - d.min < 1e5;
    const float lo = float(std::max(d.min, -1e9)), hi = float(std::min(d.max, 1e9));
    Deferred edit;
    json nv = v;
    bool changed = false;
    switch (d.type) {
        case ParamType::Bool: {
            bool b = v.get<bool>();
            if ((changed = ImGui::Checkbox(label.c_str(), &b))) nv = b;
            break;
        }
        case ParamType::Int:
        case ParamType::Float: {
            const bool is_int = d.type == ParamType::Int;
            float f = edit.get(0, float(v.get<double>()));
            // "auto" (0 or below) shows the value in use, not 0, where the pass reports it.
            const std::string format = slider_format(set_name, double(f), is_int, in_use());
            if (is_int) {
                int i = int(std::lround(f));
                if (bounded) ImGui::SliderInt(label.c_str(), &i, int(lo), int(hi), format.c_str());
                else ImGui::DragInt(label.c_str(), &i, 1.0f, int(std::max(lo, -2e9f)), int(std::min(hi, 2e9f)), format.c_str());
                f = float(i);
            } else if (bounded) {
                ImGui::SliderFloat(label.c_str(), &f, lo, hi, format.c_str());
            } else {
                ImGui::DragFloat(label.c_str(), &f, std::max(std::fabs(f) * 0.01f, 0.001f), lo, hi, format.c_str());
            }
            if ((changed = edit.track(&f, 1))) nv = is_int ? json(int(std::lround(f))) : json(double(f));
            break;
        }
        case ParamType::Enum: {
            const std::string cur = v.get<std::string>();
            if (ImGui::BeginCombo(label.c_str(), cur.c_str())) {
                for (const auto& c : d.choices)
                    if (ImGui::Selectable(c.c_str(), c == cur) && c != cur) changed = true, nv = c;
                ImGui::EndCombo();
            }
            break;
        }
        case ParamType::Color:
        case ParamType::Vec3: {
            float c[3];
            for (int k = 0; k < 3; ++k) c[k] = edit.get(k, float(v.at(k).get<double>()));
            if (d.type == ParamType::Color) ImGui::ColorEdit3(label.c_str(), c);
            else ImGui::DragFloat3(label.c_str(), c, 0.01f);
            if ((changed = edit.track(c, 3))) nv = json::array({c[0], c[1], c[2]});
            break;
        }
        case ParamType::String: ImGui::Text("%s = %s", label.c_str(), v.get<std::string>().c_str()); break;
    }
    tooltip(d);
    if (changed) out.sets.emplace_back(set_name, set_text(d.type, nv));
    ImGui::PopID();
}

}  // namespace

void draw_panels(ViewSession& session, Playback& clock, PanelInfo& info, PanelActions& out) {
    // Bottom left, clear of the overlay: the time label (top left; its text is at most ~6 % of
    // the height) and the legend (right of the data, which sits in the middle).
    const ImVec2 screen = ImGui::GetIO().DisplaySize;
    const float clear_top = std::round(0.12f * screen.y) + 24.0f;
    ImGui::SetNextWindowPos(ImVec2(8, std::max(clear_top, screen.y - 8)), ImGuiCond_FirstUseEver, ImVec2(0, 1));
    ImGui::SetNextWindowSize(ImVec2(360, std::max(120.0f, std::min(520.0f, screen.y - 8 - clear_top))), ImGuiCond_FirstUseEver);
    update_in_use(session);
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("pathlet view  (Tab hides, ? keys)");
    ImGui::TextUnformatted(info.backend.c_str());
    ImGui::Text("%s  %.1f ms", std::filesystem::path(session.graph_path()).filename().c_str(), info.frame_ms);

    // Graphs: the shipped ones, or any file; reload by hand (edits reload by themselves).
    const std::string current = std::filesystem::path(session.graph_path()).filename().string();
    if (ImGui::BeginCombo("graph", current.c_str())) {
        for (const auto& g : info.graphs) {
            const std::string name = std::filesystem::path(g).filename().string();
            if (ImGui::Selectable(name.c_str(), name == current) && name != current) out.switch_to = g;
        }
        ImGui::EndCombo();
    }
    static char path[512] = "";
    ImGui::InputTextWithHint("##file", "any graph file", path, sizeof path);
    ImGui::SameLine();
    if (ImGui::Button("open") && path[0]) out.switch_to = path;
    if (ImGui::Button("reload")) out.reload = true;
    ImGui::SameLine();
    if (ImGui::Button("copy as --set")) out.copy_command = true;
    ImGui::SameLine();
    if (ImGui::Button("reset view")) out.reset_view = true;
    if (!session.error().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
        ImGui::TextWrapped("still showing the last good graph:\n%s", session.error().c_str());
        ImGui::PopStyleColor();
    }
    if (!info.command.empty()) ImGui::TextWrapped("%s", info.command.c_str());

    if (ImGui::CollapsingHeader("time", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("play", &clock.playing);
        ImGui::SameLine();
        ImGui::Checkbox("loop", &clock.loop);
        float t = float(clock.t), speed = float(clock.speed);
        if (ImGui::SliderFloat("t (s)", &t, float(clock.t_min), float(clock.t_max), "%.2f")) clock.t = t;
        if (ImGui::SliderFloat("speed", &speed, 0.05f, 8.0f, "x%.2f", ImGuiSliderFlags_Logarithmic)) clock.speed = speed;
    }
    if (ImGui::CollapsingHeader("graph variables", ImGuiTreeNodeFlags_DefaultOpen))
        for (const auto& v : session.graph().variables) param_widget(v.name, v.name, v.decl, session.value(v.name), out);
    if (ImGui::CollapsingHeader("passes")) {
        for (const auto& p : session.compiled().passes) {
            if (!ImGui::TreeNode(p.name.c_str(), "%s (%s)", p.name.c_str(), p.type->type.c_str())) continue;
            for (const auto& d : p.type->params) param_widget(p.name + "." + d.name, d.name, d, p.params.value(d.name, json()), out);
            ImGui::TreePop();
        }
    }
    if (ImGui::CollapsingHeader("timing", ImGuiTreeNodeFlags_DefaultOpen)) {
        double total = 0;
        for (const auto& t : info.timing) total += t.ms;
        for (const auto& t : info.timing) {
            char overlay[64];
            std::snprintf(overlay, sizeof overlay, "%.1f ms", t.ms);
            ImGui::ProgressBar(total > 0 ? float(t.ms / total) : 0.0f, ImVec2(170, 0), overlay);
            ImGui::SameLine();
            ImGui::TextUnformatted(t.name.c_str());
        }
    }
    ImGui::End();
}

}  // namespace pathlet::view
