#version 460
#extension GL_GOOGLE_include_directive : require
// Precision/Recall pixel counts (Neubert 2012 §7.2.2): reference coverage (full detail) vs test
// coverage (pruned), both RGBA8 frames copied into buffers; covered = red channel > 127.
#include "gpu_types.h"

layout(local_size_x = PR_GROUP_SIZE) in;
layout(set = 0, binding = BINDING_COVERAGE_REFERENCE, std430) readonly buffer Reference { uint reference[]; };
layout(set = 0, binding = BINDING_COVERAGE_TEST, std430) readonly buffer Test { uint test[]; };
layout(set = 0, binding = BINDING_PR_COUNTS, std430) buffer Counts { PrCounts pr[]; };
layout(push_constant) uniform Push { PrCountPush push; };

shared uint group_tp, group_fp, group_fn;

void main() {
  if (gl_LocalInvocationIndex == 0) { group_tp = 0; group_fp = 0; group_fn = 0; }
  barrier();
  uint i = gl_GlobalInvocationID.x;
  if (i < push.pixel_count) {
    bool relevant = (reference[push.reference_offset + i] & 0xffu) > 127u;
    bool retrieved = (test[i] & 0xffu) > 127u;
    if (push.branch_offset != PR_NO_MASK) retrieved = retrieved || (reference[push.branch_offset + i] & 0xffu) > 127u;
    if (relevant && retrieved) atomicAdd(group_tp, 1);
    else if (retrieved) atomicAdd(group_fp, 1);
    else if (relevant) atomicAdd(group_fn, 1);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0) {
    atomicAdd(pr[push.result].tp, group_tp);
    atomicAdd(pr[push.result].fp, group_fp);
    atomicAdd(pr[push.result].fn, group_fn);
  }
}
