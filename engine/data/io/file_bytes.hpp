// Whole-file input (one read) and content sniffing shared by the pathline and mesh loaders.
#pragma once

#include <string>
#include <string_view>

namespace pathlet::io {

// The whole file in one read. DataError "<file>: byte 0: cannot open: ..." on failure.
std::string read_file_bytes(const std::string& path);

enum class Sniffed { Unknown, VtkLegacy, VtkXml, Native, Gltf, Glb, StlAscii, StlBinary, Obj, TextRows, TrackVis, MrtrixTck };
// Decides by content first; the extension only breaks ties (e.g. STL "solid" vs. text).
Sniffed sniff(std::string_view bytes, const std::string& path);
const char* sniffed_name(Sniffed s);
std::string lower_extension(const std::string& path);  // ".vtk", "" when none

}  // namespace pathlet::io
