// The panels of `pathlet view` (Dear ImGui, Debian's libimgui-dev): generated from the pass
// declarations and the graph's variables, the same declarations that drive validation and
// --set. A change goes back to the session as a --set, so "copy as --set" reproduces the view.
#pragma once

#include "view/orbit_view.hpp"
#include "view/view_session.hpp"

#include <string>
#include <utility>
#include <vector>

namespace pathlet::view {

struct PassTiming {
    std::string name;
    double ms = 0;
};

// What the panels show that the session does not know.
struct PanelInfo {
    std::string backend;                 // GL renderer and timing backend
    std::vector<PassTiming> timing;      // median over the last frames
    double frame_ms = 0;
    std::vector<std::string> graphs;     // shipped graph files to switch between
    std::string command;                 // the last "copy as --set" text
};

// What the user asked for this frame.
struct PanelActions {
    std::vector<std::pair<std::string, std::string>> sets;  // NAME, VALUE as --set
    std::string switch_to;                                  // a graph file
    bool reload = false, copy_command = false, reset_view = false;
};

void draw_panels(ViewSession& session, Playback& clock, PanelInfo& info, PanelActions& out);

// A parameter value as --set text (true, 0.25, viridis, #ff8000, [1,0,0]).
std::string set_text(ParamType type, const json& v);

}  // namespace pathlet::view
