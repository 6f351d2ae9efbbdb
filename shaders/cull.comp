#version 460
#extension GL_GOOGLE_include_directive : require
// One thread per tree instance: frustum test of the bounding sphere, then append the
// compacted indirect draws (branches, and the model's leaves as instances of its card).
#include "common.glsl"

layout(local_size_x = CULL_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COMMANDS, std430) writeonly buffer Commands { DrawCommand commands[]; };
layout(set = 0, binding = BINDING_DRAW_COUNTS, std430) buffer Counts { DrawCounts counts; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= frame.instance_count) return;
  Instance inst = instances[i];
  Model m = models[inst.model];
  float s = inst.position_scale.w;
  vec3 center = inst.position_scale.xyz + rotate_yaw(m.bounding_sphere.xyz, inst.yaw_cos_sin) * s;
  float radius = m.bounding_sphere.w * s;
  for (int p = 0; p < 6; ++p)
    if (dot(frame.frustum[p].xyz, center) + frame.frustum[p].w < -radius) return;

  uint b = atomicAdd(counts.branch_draws, 1);
  commands[b] = DrawCommand(m.branch_index_count, 1, m.branch_first_index, m.branch_vertex_offset, 0, i);
  if (m.leaf_count > 0) {
    uint l = atomicAdd(counts.leaf_draws, 1);
    atomicAdd(counts.leaves_drawn, m.leaf_count);
    commands[frame.leaf_command_base + l] =
        DrawCommand(m.card_index_count, m.leaf_count, m.card_first_index, m.card_vertex_offset, m.leaf_offset, i);
  }
}
