// Pipeline-statistics queries (VK_QUERY_TYPE_PIPELINE_STATISTICS), one per frame pass:
// what the GPU actually processed, to check against the indirect draw counts and print with
// `forest render --stats`. Devices without the pipelineStatisticsQuery feature report
// `available = false` ("n/a").
#pragma once
#include <cstdint>

#include <vulkan/vulkan.h>

namespace forest {

namespace vk {
struct Context;
}

enum class StatsPass : uint32_t { cull = 0, draw = 1 };
constexpr uint32_t kStatsPassCount = 2;

struct PipelineStats {
  bool available = false;
  uint64_t ia_vertices = 0, ia_primitives = 0;         // input assembly
  uint64_t vs_invocations = 0;
  uint64_t clip_invocations = 0, clip_primitives = 0;  // primitives entering / leaving clipping
  uint64_t fs_invocations = 0;
  uint64_t cs_invocations = 0;                        // cull pass only
};

struct GpuStatsQueries {  // null pools when the device lacks the feature
  VkQueryPool cull = VK_NULL_HANDLE;  // compute invocations
  VkQueryPool draw = VK_NULL_HANDLE;  // input assembly, vertex, clipping, fragment
};

GpuStatsQueries create_gpu_stats(vk::Context& ctx);
void destroy_gpu_stats(vk::Context& ctx, GpuStatsQueries& q);
// Outside any render pass, before the first begin of the frame.
void reset_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q);
// Both outside a rendering instance (a query may not span its boundary).
void begin_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q, StatsPass pass);
void end_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q, StatsPass pass);
// After the frame's fence: waits for the results of one pass.
PipelineStats read_gpu_stats(vk::Context& ctx, const GpuStatsQueries& q, StatsPass pass);

}  // namespace forest
