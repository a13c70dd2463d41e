#pragma once
// OpenGL core entry points, linked directly from glvnd's libOpenGL (which exports every core
// function up to 4.6, so no loader such as libepoxy is needed), and EGL.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
