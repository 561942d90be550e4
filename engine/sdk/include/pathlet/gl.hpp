// GL 4.5 core entry points straight from glvnd's libOpenGL (it exports everything up to
// 4.5), so no loader library is needed.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
