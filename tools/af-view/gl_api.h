#pragma once
// OpenGL 3.3 core for af-view: the functions straight from the system's libGL, whose Linux builds
// (Mesa, libglvnd) export every core entry point, so no loader is needed there. GLFW is told not
// to include a GL header of its own (GLFW_INCLUDE_NONE, set by the build).

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
