#version 460
#extension GL_GOOGLE_include_directive : require
// Bark, and leaves without MSAA (alpha test): tree_frag.glsl.
#include "tree_frag.glsl"
