#version 460
#extension GL_GOOGLE_include_directive : require
// Leaves: one indirect draw per visible tree drawing its leaves [0, k) as instances of the
// model's leaf card; gl_InstanceIndex (which includes firstInstance) is the leaf. A partly
// occluded tree has a second draw, of the leaves tail_cull.comp kept, listed by index.
#extension GL_ARB_shader_draw_parameters : require
#include "common.glsl"
#include "draw_push.glsl"

layout(set = 0, binding = BINDING_COMMANDS, std430) readonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_TAIL_LEAVES, std430) readonly buffer TailLeaves { uint tail_leaves[]; };

layout(location = ATTR_POSITION) in vec3 in_position;
layout(location = ATTR_NORMAL) in vec3 in_normal;
layout(location = ATTR_UV) in vec2 in_uv;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec3 out_albedo;
layout(location = 3) out vec2 out_ao_translucency;
layout(location = 4) out vec3 out_uv_layer;

float hash(uint x) {
  x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
  return float(x) / 4294967295.0;
}

void main() {
  DrawCommand d = commands[draw.command_base + gl_DrawIDARB];
  Instance inst = instances[d.instance];
  Model m = models[inst.model];
  uint leaf_index = d.leaf_list == LEAF_LIST_TAIL ? tail_leaves[gl_InstanceIndex] : uint(gl_InstanceIndex);
  Leaf leaf = leaves[leaf_index];
  // Pruning: survivors grow by sqrt(s) (s scales area); the last leaves of the prefix are in
  // the transition band and shrink toward its end.
  float prefix_index = float(leaf_index - m.leaf_offset);
  float size = leaf.position_scale.w * sqrt(d.area_scale) *
               transition_size(prefix_index, d.lambda * float(m.leaf_count), frame.prune.y);
  vec3 local = rotate_quat(leaf.rotation, in_position * size) + leaf.position_scale.xyz;
  vec3 world = rotate_yaw(local, inst.yaw_cos_sin) * inst.position_scale.w + inst.position_scale.xyz;
  out_world = world;
  out_normal = rotate_yaw(rotate_quat(leaf.rotation, in_normal), inst.yaw_cos_sin);
  vec4 tint = unpack_tint(inst.tint);
  float v = 0.85 + 0.3 * hash(leaf_index);
  out_albedo = m.leaf_color.rgb * leaf.color.rgb * tint.rgb * tint.a * v;
  out_uv_layer = vec3(in_uv, float(m.leaf_texture_layer));
  if ((frame.view_flags & VIEW_LAMBDA) != 0) out_albedo = lambda_color(d.shown_lambda);
  // Leaves deep inside the crown see less sky: a cheap occlusion term from the crown sphere.
  float depth = length(local - m.bounding_sphere.xyz) / max(m.bounding_sphere.w, 1e-3);
  out_ao_translucency = vec2(mix(0.35, 1.0, clamp(depth * 1.3 - 0.2, 0.0, 1.0)), 0.45);
  gl_Position = draw_view_proj() * vec4(world, 1.0);
}
