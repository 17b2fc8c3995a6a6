#pragma once
// One way to reach OpenGL for every viewer file: GLFW without its own GL
// include, then the system headers with prototypes. Linux's libGL (glvnd)
// exports the entry points the viewer uses (3.3 core), so no loader is needed.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
