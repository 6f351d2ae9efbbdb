#version 460
#extension GL_GOOGLE_include_directive : require
// Leaves with MSAA: tree_frag.glsl writing its own sample mask from the leaf alpha. A shader of
// its own, not a specialization of tree.frag, so that bark never declares gl_SampleMask (a
// fragment shader that writes it may lose early depth tests on some GPUs).
#define LEAF_MSAA
#include "tree_frag.glsl"
