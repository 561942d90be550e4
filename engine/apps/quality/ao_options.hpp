// The ray-traced AO measure's options, said once: `pathlet quality` declares --NAME (its '_' as
// '-') from this table and Python's pathlet.quality() takes NAME= from it; the defaults are
// QualityOptions' own.
#pragma once

#include "measure.hpp"

#include <variant>
#include <vector>

namespace pathlet::quality {

struct AoOption {
    const char* name;     // Python's spelling; the command's has '-' for '_'
    const char* metavar;  // "" for a flag
    const char* doc;
    std::variant<int QualityOptions::*, float QualityOptions::*, bool QualityOptions::*> field;
};

inline const std::vector<AoOption>& ao_options() {
    static const std::vector<AoOption> table = {
        {"rays", "N", "ray-traced AO: rays per pixel", &QualityOptions::rays},
        {"flicker_rays", "N",
         "ray-traced AO of every frame, for the flicker against the reference's own change: rays per pixel (0: not "
         "measured)",
         &QualityOptions::flicker_rays},
        {"max_distance", "WIDTHS", "ray-traced AO: ray length in line widths", &QualityOptions::max_distance},
        {"include_own_line", "", "ray-traced AO: a pixel's own line occludes it too", &QualityOptions::own_line},
        {"gbuffer_point", "",
         "ray-traced AO: rays start at the G-buffer's depth and normal (halos pushed back), not where the pixel's ray "
         "meets its line's round tube",
         &QualityOptions::gbuffer_point},
        {"depth_tolerance", "D", "flicker: largest change of linear depth that counts as unchanged",
         &QualityOptions::depth_tolerance},
    };
    return table;
}

}  // namespace pathlet::quality
