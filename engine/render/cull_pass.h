// The cull/prune pass (shaders/cull.comp), one thread per tree instance: frustum and
// occlusion culling, the branch LOD by projected error, the leaf prefix λ and its area scale
// (Neubert 2012 ch7, Cook et al. 2007), written as compacted indirect draws. It also owns
// the per-instance occlusion state that cull.comp reads and rewrites every frame.
#pragma once
#include <cstdint>

#include "engine/render/descriptor_table.h"
#include "gpu_types.h"

namespace forest {

struct CullPass {
  VkPipeline pipeline = VK_NULL_HANDLE;
  uint32_t instance_count = 0;
  // DrawCommand: [0, n) one branch draw per visible tree, [n, 3n) leaf draws (the prefix and,
  // with occlusion, the tail of visible leaves). n = instance_count.
  vk::Buffer commands;
  vk::Buffer counts;           // DrawCounts: the draw counts and statistics
  vk::Buffer instance_states;  // InstanceState per instance: occlusion feedback
};

inline constexpr Binding kCullBindings[] = {
    {BINDING_COMMANDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_DRAW_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_INSTANCE_STATE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_DEPTH_PYRAMID, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_TAIL_JOBS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
};

CullPass create_cull_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count);
void destroy_cull_pass(vk::Context& ctx, CullPass& pass);
void write_cull_bindings(DescriptorWrites& writes, const CullPass& pass);

// Clears the counts and dispatches cull.comp (set 0 bound by the caller). After: the
// commands and counts are written by compute; the caller orders their readers.
void record_cull_pass(VkCommandBuffer cmd, const CullPass& pass);

}  // namespace forest
