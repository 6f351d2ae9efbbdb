// The tail cull pass (shaders/tail_cull.comp): with occlusion on, the leaves the cull pass
// drops from a partly hidden tree (its prefix beyond λ·o) are tested one by one against the
// previous frame's depth pyramid, and those it could see are drawn by a second leaf draw of
// that tree (Neubert 2012 §7.4 [ours]: per-leaf instead of prefix-only). One workgroup per
// TailJob, dispatched indirectly from the counts the cull pass wrote.
#pragma once
#include <cstdint>

#include "engine/render/cull_pass.h"

namespace forest {

struct TailCullPass {
  VkPipeline pipeline = VK_NULL_HANDLE;
  vk::Buffer jobs;    // TailJob, at most one per instance
  vk::Buffer leaves;  // uint leaf indices of the visible tails, in priority order
  uint32_t capacity = 1;  // entries of `leaves`
};

inline constexpr Binding kTailCullBindings[] = {
    {BINDING_COMMANDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_DRAW_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_INSTANCE_STATE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_DEPTH_PYRAMID, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_TAIL_JOBS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_TAIL_LEAVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
};

// `instance_leaves`: Σ over instances of its model's leaf count; the tail buffer holds that
// many entries up to kMaxTailLeaves (generators/core/limits.h). A tree that finds no room
// left draws its whole prefix.
TailCullPass create_tail_cull_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count,
                                   uint64_t instance_leaves);
void destroy_tail_cull_pass(vk::Context& ctx, TailCullPass& pass);
void write_tail_cull_bindings(DescriptorWrites& writes, const TailCullPass& pass);

// After record_cull_pass: orders the cull writes before the indirect dispatch, then runs it.
void record_tail_cull_pass(VkCommandBuffer cmd, const TailCullPass& pass, const CullPass& cull);

}  // namespace forest
