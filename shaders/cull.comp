#version 460
#extension GL_GOOGLE_include_directive : require
// One thread per tree instance: frustum test of the bounding sphere, branch LOD by projected
// error, then append the compacted indirect draws (branches, and the model's leaves as
// instances of its card).
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

  // Coarsest level whose error, projected at the sphere's nearest point, stays under the
  // allowed pixels (errors are non-decreasing along the chain).
  float dist = max(distance(center, frame.camera_pos.xyz) - radius, 1e-3);
  uint lod = 0;
  for (uint k = 1; k < m.lod_count; ++k)
    if (m.lod_error[k] * s * frame.lod.x / dist <= frame.lod.y) lod = k;

  uint b = atomicAdd(counts.branch_draws, 1);
  atomicAdd(counts.lod_draws[lod], 1);
  atomicAdd(counts.branch_triangles, m.lod_index_count[lod] / 3);
  commands[b] = DrawCommand(m.lod_index_count[lod], 1, m.lod_first_index[lod], m.lod_vertex_offset[lod], 0, i);
  if (m.leaf_count > 0) {
    uint l = atomicAdd(counts.leaf_draws, 1);
    atomicAdd(counts.leaves_drawn, m.leaf_count);
    commands[frame.leaf_command_base + l] =
        DrawCommand(m.card_index_count, m.leaf_count, m.card_first_index, m.card_vertex_offset, m.leaf_offset, i);
  }
}
