// What this build has and where it runs from: `pathlet --version` (and `info`), the Python
// module's pathlet.build_info(). A bundle (scripts/bundle.sh) is recognised by the marker file
// bundle.txt in the share folder beside libpathlet.
#pragma once

#include <string>

namespace pathlet {

// Lines "build: ...", "runs from: ...", "share: ..." (no trailing newline on the last).
std::string build_description();

// The bundle's marker line ("pathlet bundle (lean) ...") when libpathlet runs from a bundle, else "".
std::string bundle_marker();

}  // namespace pathlet
