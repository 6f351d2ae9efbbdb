// The coverage count pass (shaders/pr_count.comp): tp / fp / fn pixel counts of a test
// coverage frame against a reference (Precision/Recall, Neubert 2012 §7.2.2), on the GPU,
// so only three numbers come back. It owns the coverage buffers: references (one per view,
// and for batched bakes the branch-only mask of that view), the test frame and the counts.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/render/descriptor_table.h"
#include "gpu_types.h"

namespace forest {

struct PrCountPass {
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDeviceSize frame_bytes = 0;  // one RGBA8 coverage frame
  vk::Buffer reference, test, counts, readback;
  uint32_t reference_capacity = 1, result_capacity = 1;  // frames / PrCounts allocated
};

inline constexpr Binding kPrCountBindings[] = {
    {BINDING_COVERAGE_REFERENCE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_COVERAGE_TEST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_PR_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
};
// Its push constants (the only ones of the shared pipeline layout).
inline constexpr VkPushConstantRange kPrCountPushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::PrCountPush)};

PrCountPass create_pr_count_pass(vk::Context& ctx, VkPipelineLayout layout, VkExtent2D frame);
void destroy_pr_count_pass(vk::Context& ctx, PrCountPass& pass);
void write_pr_count_bindings(DescriptorWrites& writes, const PrCountPass& pass);
// Grows the buffers; returns true when they were replaced (their bindings must be rewritten,
// after every submit that used them has finished).
bool reserve_pr_count(vk::Context& ctx, PrCountPass& pass, uint32_t reference_frames, uint32_t results);

// Dispatches one comparison (set 0 bound to the compute bind point by the caller). Before:
// the frames and the zeroed counts are visible to compute; after: the counts are written.
void record_pr_count_pass(VkCommandBuffer cmd, const PrCountPass& pass, VkPipelineLayout layout,
                          const gpu::PrCountPush& push);
// Copies `count` results to the readback buffer and makes them visible to the host.
void record_pr_readback(VkCommandBuffer cmd, const PrCountPass& pass, uint32_t count);
std::vector<gpu::PrCounts> read_pr_counts(const PrCountPass& pass, uint32_t count);

}  // namespace forest
