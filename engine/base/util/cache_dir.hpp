// Where Pathlet keeps what it can make again (the phantom, which graph wrote an output folder):
// $XDG_CACHE_HOME/pathlet (an absolute XDG_CACHE_HOME only: the XDG spec says to ignore a
// relative one), else ~/.cache/pathlet, else, without HOME, the user's own folder in the
// temporary directory (pathlet-cache-UID, mode 0700), made if missing and refused when it is
// not a directory of this user's that only this user may write: a folder another user made or
// linked there could plant the files Pathlet reads back.
#pragma once

#include <string>

namespace pathlet {

// Throws std::runtime_error naming the folder when the temporary-directory fallback is unsafe.
std::string cache_dir();

}  // namespace pathlet
