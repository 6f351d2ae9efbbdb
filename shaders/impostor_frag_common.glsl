// What impostor.frag and impostor_shadow.frag share: the tree's instance, the pixel's ray and
// the blended hit in model space, the dithered cross-fade, and the hit's world point.
#include "common.glsl"
#include "draw_push.glsl"
#include "impostor_sample.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) flat in uint in_instance;
layout(location = 2) flat in float in_fade;
layout(location = 3) flat in uvec3 in_views;
layout(location = 4) flat in vec3 in_weights;

struct ImpostorPixel {
  Instance inst;
  ImpostorHit hit;
  vec3 world;   // the hit in world space
};

// The pixel's hit; false where it shows no tree or where the cross-fade gives the pixel to the
// mesh. A pixel shows the tree where the blended coverage passes the model's cutoff, which the
// bake chose for the best Q (impostor_bake.h): a far crown's texels average sparse leaves to
// a coverage below one half, which a cutoff of one half drops (broadleaf: recall 0.80,
// precision 0.93 at 64 px). Showing a pixel with the probability of its coverage instead keeps
// the expected coverage but scatters false pixels both ways (Q 0.79 → 0.67 there).
bool impostor_pixel(out ImpostorPixel px) {
  px.inst = instances[in_instance];
  // The model's fields, not the whole Model, per pixel (leaf_body.glsl says why).
  const vec4 sphere = models[px.inst.model].bounding_sphere;
  float s = px.inst.position_scale.w;
  vec2 inverse_yaw = vec2(px.inst.yaw_cos_sin.x, -px.inst.yaw_cos_sin.y);
  vec3 center = px.inst.position_scale.xyz + rotate_yaw(sphere.xyz, px.inst.yaw_cos_sin) * s;
  vec3 ray_world = draw.cascade == SHADOW_NONE ? normalize(in_world - frame.camera_pos.xyz) : -frame.sun_dir.xyz;
  vec3 rel = rotate_yaw(in_world - center, inverse_yaw) / s;
  px.hit = impostor_hit(sphere.w, models[px.inst.model].impostor_layer, in_views, in_weights, rel, rotate_yaw(ray_world, inverse_yaw));
  px.world = center + rotate_yaw(px.hit.point, px.inst.yaw_cos_sin) * s;
  float cutoff = frame.impostor.z > 0.0 ? frame.impostor.z : models[px.inst.model].impostor_cutoff;
  if (px.hit.alpha < cutoff) return false;
  // The mesh keeps the pixels below its fade 1 − in_fade (tree.frag), the impostor the rest.
  return in_fade >= 1.0 || dither_threshold(gl_FragCoord.xy) >= 1.0 - in_fade;
}

// Depth of the hit, so impostors meet the terrain, each other and the depth pyramid where
// the tree is, not where its quad is.
float impostor_depth(vec3 world) {
  vec4 clip = draw_view_proj() * vec4(world, 1.0);
  return clamp(clip.z / clip.w, 0.0, 1.0);
}
