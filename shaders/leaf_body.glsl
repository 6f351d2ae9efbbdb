// The leaf vertex shader's body, compiled twice: leaf.vert draws each leaf as an instance of
// the model's card (vertex attributes), leaf_pulled.vert (LEAF_PULLED) pulls the card's
// corners from Model.card_corners by gl_VertexIndex (leaf_draw.glsl). Either way a leaf is
// one triangle around its card.
// A partly occluded tree has a second draw, of the leaves tail_cull.comp kept, listed by index.
#include "common.glsl"
#include "draw_push.glsl"
#include "crown_light.h"

layout(set = 0, binding = BINDING_COMMANDS, std430) readonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_TAIL_LEAVES, std430) readonly buffer TailLeaves { uint tail_leaves[]; };

#ifndef LEAF_PULLED
layout(location = ATTR_POSITION) in vec3 in_position;
layout(location = ATTR_NORMAL) in vec3 in_normal;
layout(location = ATTR_UV) in vec2 in_uv;
#endif
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_albedo;
layout(location = 3) out vec2 out_ao_translucency;
layout(location = 4) out vec3 out_uv_layer;
layout(location = 5) out float out_sun_visibility;
layout(location = 6) flat out float out_fade;

float hash(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x) / 4294967295.0;
}

void main() {
  DrawCommand d = commands[draw.command_base + gl_DrawIDARB];
  Instance inst = instances[d.instance];
  // The model's fields are read where used, never the whole Model: with `Model m = models[..]`
  // lavapipe kept the copy of all ~90 words per vertex (likely because card_corners is indexed
  // at run time), 1.23-1.29x of a walk.toml frame (bench/results/leaf_vertex_cost.md).
  const uint model = inst.model;
#ifdef LEAF_PULLED
  // Vertex pulling (leaf_draw.glsl): item = vertex / 4, the triangle's corner = vertex % 4.
  uint item = uint(gl_VertexIndex) >> 2;
  vec4 corner = models[model].card_corners[uint(gl_VertexIndex) & 3u];
  vec3 in_position = vec3(corner.xy, 0.0), in_normal = vec3(0.0, 0.0, 1.0);
  vec2 in_uv = corner.zw;
#else
  uint item = uint(gl_InstanceIndex);
#endif
  uint leaf_index = d.leaf_list == LEAF_LIST_TAIL ? tail_leaves[item] : item;
  Leaf leaf = leaves[leaf_index];
  // Pruning: survivors grow by sqrt(s) (s scales area); the last leaves of the prefix are in
  // the transition band and shrink toward its end.
  float prefix_index = float(leaf_index - models[model].leaf_offset);
  float size = leaf.position_scale.w * sqrt(d.area_scale) *
               transition_size(prefix_index, d.lambda * float(models[model].leaf_count), frame.prune.y);
  vec3 local = rotate_quat(leaf.rotation, in_position * size) + leaf.position_scale.xyz;
  vec3 world = rotate_yaw(local, inst.yaw_cos_sin) * inst.position_scale.w + inst.position_scale.xyz;
  out_world = world;
  out_normal = rotate_yaw(rotate_quat(leaf.rotation, in_normal), inst.yaw_cos_sin);
  vec4 tint = unpack_tint(inst.tint);
  float v = 0.85 + 0.3 * hash(leaf_index);
  out_albedo = models[model].leaf_color.rgb * leaf.color.rgb * tint.rgb * tint.a * v;
  out_uv_layer = vec3(in_uv, float(models[model].leaf_texture_layer));
  if ((frame.view_flags & VIEW_LAMBDA) != 0) out_albedo = lambda_color(d.shown_lambda);
  out_sun_visibility = 1.0;
  out_fade = d.fade;
  out_ao_translucency = vec2(1.0, 0.45);
  // The shadow map and coverage (mask) frames need the position and uv alone.
  if (draw.cascade != SHADOW_NONE || (frame.view_flags & VIEW_MASK) != 0) {
    gl_Position = draw_view_proj() * vec4(world, 1.0);
    return;
  }
  // Crown self-shadowing (crown_light.h): the leaf's baked depths below the hull, or unbaked
  // the exit distances from the bounding sphere; the sun direction in model space (the
  // inverse yaw; uniform scale does not turn it).
  float kappa = models[model].crown_extinction;
  vec3 crown_pos, crown_neg;
  if (kappa > 0.0) {
    vec2 dx = unpackHalf2x16(leaf.crown_depth.x), dy = unpackHalf2x16(leaf.crown_depth.y),
         dz = unpackHalf2x16(leaf.crown_depth.z);
    crown_pos = vec3(dx.x, dy.x, dz.x);
    crown_neg = vec3(dx.y, dy.y, dz.y);
  } else {
    kappa = CROWN_FALLBACK_OPTICAL_DEPTH / max(models[model].bounding_sphere.w, 1e-3);
    crown_pos = crown_sphere_pos(local, models[model].bounding_sphere.xyz, models[model].bounding_sphere.w);
    crown_neg = crown_sphere_neg(local, models[model].bounding_sphere.xyz, models[model].bounding_sphere.w);
  }
  // κ·D is the same at any instance scale (leaf area ∝ s², volume ∝ s³, paths ∝ s).
  vec3 sun_model = rotate_yaw(frame.sun_dir.xyz, vec2(inst.yaw_cos_sin.x, -inst.yaw_cos_sin.y));
  out_sun_visibility = crown_sun_transmittance(crown_pos, crown_neg, kappa, sun_model);
  out_ao_translucency = vec2(crown_ambient(crown_sky_visibility(crown_pos, crown_neg, kappa)), 0.45);
  gl_Position = draw_view_proj() * vec4(world, 1.0);
}
