#include "view/view_script.hpp"

#include "util/text.hpp"

#include <pathlet/scene.hpp>

#include <algorithm>
#include <stdexcept>

namespace pathlet::view {

std::vector<ScriptEvent> load_script(const std::string& path) {
    return parse_script(text::read_json_text(path, "view script"), path);
}

std::vector<ScriptEvent> parse_script(const std::string& text, const std::string& path) {
    const nlohmann::json j = text::parse_json_of(path, text, "view script");
    if (!j.is_array()) throw DataError(path + ":/: a view script is an array of events");
    static const std::vector<std::string> keys{"space", "left", "right", "up", "down", "r", "l", "s", "?"};
    std::vector<ScriptEvent> out;
    for (size_t i = 0; i < j.size(); ++i) {
        const nlohmann::json& e = j[i];
        const std::string at = path + ":/" + std::to_string(i);
        auto bad = [&](const std::string& why) { throw DataError(at + ": " + why + ", got " + e.dump()); };
        if (!e.is_object() || !e.contains("frame") || !e["frame"].is_number_integer() || e["frame"].get<long>() < 0 ||
            e["frame"].get<long>() > 1000000000L)
            bad("an event needs \"frame\": a shown frame number in 0..1e9");
        ScriptEvent ev;
        ev.frame = e["frame"].get<long>();
        if (e.contains("key")) {
            if (!e["key"].is_string() || std::find(keys.begin(), keys.end(), e["key"].get<std::string>()) == keys.end())
                bad("\"key\" must be one of space, left, right, up, down, r, l, s, ?");
            ev.key = e["key"].get<std::string>();
        } else if (e.contains("drag")) {
            const auto& d = e["drag"];
            if (!d.is_array() || d.size() != 2 || !d[0].is_number() || !d[1].is_number()) bad("\"drag\" must be [dx, dy] in pixels");
            ev.dx = float(std::clamp(d[0].get<double>(), -1e5, 1e5));
            ev.dy = float(std::clamp(d[1].get<double>(), -1e5, 1e5));
            ev.button = e.contains("button") && e["button"].is_string() ? e["button"].get<std::string>()
                        : e.contains("button")                            ? std::string("?")
                                                                          : std::string("left");
            if (ev.button != "left" && ev.button != "right" && ev.button != "middle") bad("\"button\" must be left, right or middle");
        } else if (e.contains("scroll")) {
            if (!e["scroll"].is_number()) bad("\"scroll\" must be a number of wheel steps");
            ev.scroll = float(std::clamp(e["scroll"].get<double>(), -1e3, 1e3));
        } else if (e.contains("set")) {
            if (!e["set"].is_string() || e["set"].get<std::string>().find('=') == std::string::npos)
                bad("\"set\" must be \"NAME=VALUE\" as for --set");
            ev.set = e["set"].get<std::string>();
        } else if (e.contains("graph")) {
            if (!e["graph"].is_string() || e["graph"].get<std::string>().empty()) bad("\"graph\" must be a graph file");
            ev.graph = e["graph"].get<std::string>();
        } else if (e.contains("reload")) {
            if (!e["reload"].is_boolean()) bad("\"reload\" must be true");
            ev.reload = e["reload"].get<bool>();
        } else {
            bad("an event needs \"key\", \"drag\", \"scroll\", \"set\", \"graph\" or \"reload\"");
        }
        out.push_back(ev);
    }
    return out;
}

}  // namespace pathlet::view
