#pragma once
/// OpenGL 3.3 core entry points, resolved by glvnd's libOpenGL (the same entry points
/// serve a GLFW window's GLX context and an EGL off-screen context). Include only from
/// render/*.cpp and the viewer.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
