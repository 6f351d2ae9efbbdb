#version 460
#extension GL_GOOGLE_include_directive : require
// A far tree's impostor (impostor_pass.h): the blended views' albedo (which holds the leaves'
// sky visibility), lit by the sun through the shadow map with the blended model-space normal
// turned by the instance's yaw, as tree.frag lights leaves; white in coverage frames; a
// colour of its own in the λ view.
#include "impostor_frag_common.glsl"
#include "lighting.glsl"

layout(location = 0) out vec4 out_color;

// Light through the impostor's leaves, a little less than a leaf's own (0.45, leaf.vert):
// the atlas also holds bark.
const float kImpostorTranslucency = 0.35;

void main() {
  ImpostorPixel px;
  if (!impostor_pixel(px)) discard;
  gl_FragDepth = impostor_depth(px.world);
  if ((frame.view_flags & VIEW_MASK) != 0) {
    out_color = vec4(1.0);
    return;
  }
  vec3 n = rotate_yaw(px.hit.normal, px.inst.yaw_cos_sin);
  vec3 to_camera = frame.camera_pos.xyz - px.world;
  if (dot(n, to_camera) < 0.0) n = -n;  // blended views may disagree on a thin leaf's side
  if ((frame.view_flags & VIEW_LAMBDA) != 0) {
    out_color = vec4(tone_map(vec3(0.75, 0.2, 0.8) * 0.8), 1.0);
    return;
  }
  float sun_visibility = sun_shadow(px.world, n);
  if ((frame.view_flags & VIEW_SHADOW) != 0) {
    out_color = vec4(vec3(sun_visibility), 1.0);
    return;
  }
  vec3 albedo = px.hit.albedo * unpack_tint(px.inst.tint).rgb * unpack_tint(px.inst.tint).a;
  vec3 hdr = shade(albedo, n, px.world, 1.0, kImpostorTranslucency, sun_visibility);
  out_color = vec4(tone_map(hdr), 1.0);
}
