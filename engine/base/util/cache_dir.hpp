// Where Pathlet keeps what it can make again (the phantom, which graph wrote an output folder):
// $XDG_CACHE_HOME/pathlet, else ~/.cache/pathlet, else a folder in the temporary directory.
#pragma once

#include <string>

namespace pathlet {

std::string cache_dir();

}  // namespace pathlet
