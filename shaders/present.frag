#version 460
#extension GL_GOOGLE_include_directive : require
// forest walk's copy pass: the rendered frame, scaled into the viewport rectangle (letterbox).
// Sampling decodes sRGB and the attachment re-encodes it, so same-size copies keep the bytes.
#include "gpu_types.h"

layout(set = 0, binding = PRESENT_BINDING_RENDERED) uniform sampler2D rendered;
layout(push_constant) uniform Rect { PresentPush rect; };  // viewport, pixels
layout(location = 0) out vec4 out_color;

void main() {
  vec2 uv = (gl_FragCoord.xy - rect.offset) / rect.size;
  out_color = vec4(textureLod(rendered, uv, 0.0).rgb, 1.0);
}
