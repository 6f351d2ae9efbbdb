#version 460
#extension GL_GOOGLE_include_directive : require
// A far tree's impostor in the sun's shadow map: the quad faces the sun, the blended views'
// coverage cuts the tree out and its stored heights give the depth, so it casts the shadow
// of its crown's shape from where the crown is.
#include "impostor_frag_common.glsl"

void main() {
  ImpostorPixel px;
  if (!impostor_pixel(px)) discard;
  gl_FragDepth = impostor_depth(px.world);
}
