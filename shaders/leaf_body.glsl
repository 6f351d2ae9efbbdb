// The leaf vertex shader's body, compiled twice: leaf.vert draws each leaf as an instance of
// the model's card (vertex attributes, three vertices a leaf); leaf_pulled.vert (LEAF_PULLED)
// is one vertex a leaf, the item gl_VertexIndex (leaf_draw.glsl), a point that leaf_card.geom
// expands into the card's triangle from Model.card_corners. Either way a leaf is one triangle
// around its card. A leaf's vertex work is its buffer reads (bench/results/leaf_vertex_cost.md):
// pulled, they are made once a leaf instead of once a corner.
// A partly occluded tree has a second draw, of the leaves tail_cull.comp kept, listed by index.
#include "common.glsl"
#include "draw_push.glsl"
#include "crown_light.h"
#ifndef LEAF_CASTER  // the shadow pass's casters (leaf_caster*.vert) are not lit
#define SHADOW_EXPLICIT_LOD
#include "lighting.glsl"
#endif

layout(set = 0, binding = BINDING_COMMANDS, std430) readonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_TAIL_LEAVES, std430) readonly buffer TailLeaves { uint tail_leaves[]; };

#ifdef LEAF_PULLED
// To leaf_card.geom: the card's frame (world and clip space) and what the fragments share.
layout(location = 0) out vec4 out_origin_layer;     // world position of the card origin, texture layer
layout(location = 1) out vec4 out_normal_sun;       // world normal, sun visibility
layout(location = 2) out vec4 out_albedo_fade;      // albedo, the mesh's share of an impostor fade
layout(location = 3) out vec4 out_axis_x_ao;        // world card x axis (leaf size), ambient occlusion
layout(location = 4) out vec4 out_axis_y_translucency;
layout(location = 5) out vec4 out_clip_origin;      // clip space: origin, and the axes (w = 0 in world)
layout(location = 6) out vec4 out_clip_x;
layout(location = 7) out vec4 out_clip_y;
layout(location = 8) out vec4 out_corner[3];        // Model.card_corners
layout(location = 11) out float out_leaf_shadow;    // the shadow map at the card's centre (leaf_sun_shadow)
#else
layout(location = ATTR_POSITION) in vec3 in_position;
layout(location = ATTR_NORMAL) in vec3 in_normal;
layout(location = ATTR_UV) in vec2 in_uv;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_albedo;
layout(location = 3) out vec2 out_ao_translucency;
layout(location = 4) out vec3 out_uv_layer;
layout(location = 5) out float out_sun_visibility;
layout(location = 6) flat out vec2 out_fade_shadow;  // the impostor fade, the shadow map (leaf_sun_shadow)
#endif

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
  uint item = uint(gl_VertexIndex);  // vertex pulling (leaf_draw.glsl): one point a leaf
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
  vec3 leaf_origin = leaf.position_scale.xyz;
  vec2 yaw = inst.yaw_cos_sin;
  float scale = inst.position_scale.w;
#ifdef LEAF_PULLED
  const vec3 card_normal = vec3(0.0, 0.0, 1.0);  // pulled cards are quads in their z = 0 plane
#else
  vec3 card_normal = in_normal;
#endif
  vec3 normal = rotate_yaw(rotate_quat(leaf.rotation, card_normal), yaw);
  vec4 tint = unpack_tint(inst.tint);
  float v = 0.85 + 0.3 * hash(leaf_index);
  vec3 albedo = models[model].leaf_color.rgb * leaf.color.rgb * tint.rgb * tint.a * v;
  if ((frame.view_flags & VIEW_LAMBDA) != 0) albedo = lambda_color(d.shown_lambda);
  const float layer = float(models[model].leaf_texture_layer);
  // The card is linear in its corner p: world = origin + p.x·axis_x + p.y·axis_y (+ p.z·axis_z
  // for a card that is not a flat quad, drawn instanced), and so is its clip position. Both
  // forms compute a corner by these sums (leaf_card.geom for pulled leaves), so that they draw
  // the same frame bit for bit (gpu.OcclusionTest.PulledAndInstancedLeavesDrawTheSameFrame).
  vec3 origin = rotate_yaw(leaf_origin, yaw) * scale + inst.position_scale.xyz;
  vec3 axis_x = rotate_yaw(rotate_quat(leaf.rotation, vec3(size, 0.0, 0.0)), yaw) * scale;
  vec3 axis_y = rotate_yaw(rotate_quat(leaf.rotation, vec3(0.0, size, 0.0)), yaw) * scale;
  float sun_visibility = 1.0, leaf_shadow = 1.0;
  vec2 ao_translucency = vec2(1.0, 0.45);
  // The shadow map and coverage (mask) frames need the position and uv alone.
#ifndef LEAF_CASTER
  if (draw.cascade == SHADOW_NONE && (frame.view_flags & VIEW_MASK) == 0) {
    // Crown self-shadowing (crown_light.h): the leaf's baked depths below the hull, or unbaked
    // the exit distances from the bounding sphere at its origin (once a leaf: its corners are
    // centimetres apart in a crown of metres); the sun direction in model space (the inverse
    // yaw; uniform scale does not turn it).
    float kappa = models[model].crown_extinction;
    vec3 crown_pos, crown_neg;
    if (kappa > 0.0) {
      vec2 dx = unpackHalf2x16(leaf.crown_depth.x), dy = unpackHalf2x16(leaf.crown_depth.y),
           dz = unpackHalf2x16(leaf.crown_depth.z);
      crown_pos = vec3(dx.x, dy.x, dz.x);
      crown_neg = vec3(dx.y, dy.y, dz.y);
    } else {
      kappa = CROWN_FALLBACK_OPTICAL_DEPTH / max(models[model].bounding_sphere.w, 1e-3);
      crown_pos = crown_sphere_pos(leaf_origin, models[model].bounding_sphere.xyz, models[model].bounding_sphere.w);
      crown_neg = crown_sphere_neg(leaf_origin, models[model].bounding_sphere.xyz, models[model].bounding_sphere.w);
    }
    // κ·D is the same at any instance scale (leaf area ∝ s², volume ∝ s³, paths ∝ s).
    vec3 sun_model = rotate_yaw(frame.sun_dir.xyz, vec2(yaw.x, -yaw.y));
    sun_visibility = crown_sun_transmittance(crown_pos, crown_neg, kappa, sun_model);
    ao_translucency.x = crown_ambient(crown_sky_visibility(crown_pos, crown_neg, kappa));
    // The shadow map once a leaf (lighting.glsl), at the card's centre (cards span y in
    // [0, 1], make_leaf_card). Not for the shadow pass's casters (leaf_caster*.vert): they draw it.
    leaf_shadow = leaf_sun_shadow(origin + 0.5 * axis_y, normal);
  }
#endif
  mat4 view_proj = draw_view_proj();
  vec4 clip_origin = view_proj * vec4(origin, 1.0);
  vec4 clip_x = view_proj * vec4(axis_x, 0.0), clip_y = view_proj * vec4(axis_y, 0.0);
#ifdef LEAF_PULLED
  out_origin_layer = vec4(origin, layer);
  out_normal_sun = vec4(normal, sun_visibility);
  out_albedo_fade = vec4(albedo, d.fade);
  out_axis_x_ao = vec4(axis_x, ao_translucency.x);
  out_axis_y_translucency = vec4(axis_y, ao_translucency.y);
  out_clip_origin = clip_origin;
  out_clip_x = clip_x;
  out_clip_y = clip_y;
  for (uint c = 0u; c < 3u; ++c) out_corner[c] = models[model].card_corners[c];
  out_leaf_shadow = leaf_shadow;
#else
  vec3 axis_z = rotate_yaw(rotate_quat(leaf.rotation, vec3(0.0, 0.0, size)), yaw) * scale;
  out_world = origin + in_position.x * axis_x + in_position.y * axis_y + in_position.z * axis_z;
  out_normal = normal;
  out_albedo = albedo;
  out_uv_layer = vec3(in_uv, layer);
  out_sun_visibility = sun_visibility;
  out_fade_shadow = vec2(d.fade, leaf_shadow);
  out_ao_translucency = ao_translucency;
  gl_Position = clip_origin + in_position.x * clip_x + in_position.y * clip_y +
                in_position.z * (view_proj * vec4(axis_z, 0.0));
#endif
}
