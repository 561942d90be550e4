// The fragment shader interlock (GL_ARB_fragment_shader_interlock, MLAB): a program whose
// fragment stage declares it gets that stage as one shader object.
#pragma once

#include <pathlet/shader_source.hpp>

#include <string>
#include <vector>

namespace pathlet {

// One shader object on its way to the driver.
struct ShaderUnit {
    std::string path;                   // its own file (for messages and dumps)
    std::string src;                    // composed source
    std::vector<std::string> files;     // the stage's files, found
    std::vector<std::string> numbered;  // files by #line number (ShaderSource::compose)
    GLenum stage = 0;
    std::string merge_note{};           // appended to a compile error of a merged object
};

// NVIDIA (580, H200) links an interlocked fragment stage of several objects into code without
// the interlock and fails ("FSIB: invalid statement"), whichever objects declare it; as one
// object it links. So the other fragment objects (a colour hook) are appended to the one that
// declares `layout(..., pixel_interlock_ordered, ...) in;` (any qualifiers, over several lines).
// The appended files keep their source-string numbers, so messages still name them. Their
// #extension lines move up under the version line (an #extension after code is an error), and a
// uniform declared the same way in both is declared once; any other declaration both make is a
// compile error whose message names the hook and says why.
void merge_interlocked_fragments(std::vector<ShaderUnit>& units, const ShaderSource& source);

}  // namespace pathlet
