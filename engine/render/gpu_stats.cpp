#include "engine/render/gpu_stats.h"

#include "engine/vk/context.h"

namespace forest {

namespace {

// Results come back in the order of the bits, lowest first. The cull pass would have a pool
// counting compute invocations, but any pipeline-statistics query around a dispatch crashes
// lavapipe (Mesa 22.3.6, segfault in its worker thread), so it is only created on other
// drivers.
constexpr VkQueryPipelineStatisticFlags kDrawFlags =
    VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_VERTICES_BIT | VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT | VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_CLIPPING_PRIMITIVES_BIT | VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
constexpr uint32_t kDrawCounters = 6;
constexpr VkQueryPipelineStatisticFlags kCullFlags = VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;

VkQueryPool pool_of(const GpuStatsQueries& q, StatsPass pass) { return pass == StatsPass::cull ? q.cull : q.draw; }

VkQueryPool create_pool(vk::Context& ctx, VkQueryPipelineStatisticFlags flags) {
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
  ci.queryCount = 1;
  ci.pipelineStatistics = flags;
  VkQueryPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateQueryPool(ctx.device, &ci, nullptr, &pool));
  return pool;
}

}  // namespace

GpuStatsQueries create_gpu_stats(vk::Context& ctx) {
  GpuStatsQueries q;
  if (!ctx.pipeline_statistics) return q;
  if (ctx.properties.vendorID != 0x10005)  // VK_VENDOR_ID_MESA: lavapipe
    q.cull = create_pool(ctx, kCullFlags);
  q.draw = create_pool(ctx, kDrawFlags);
  return q;
}

void destroy_gpu_stats(vk::Context& ctx, GpuStatsQueries& q) {
  for (VkQueryPool* p : {&q.cull, &q.draw}) {
    if (*p) vkDestroyQueryPool(ctx.device, *p, nullptr);
    *p = VK_NULL_HANDLE;
  }
}

void reset_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q) {
  for (VkQueryPool p : {q.cull, q.draw})
    if (p) vkCmdResetQueryPool(cmd, p, 0, 1);
}

void begin_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q, StatsPass pass) {
  if (VkQueryPool p = pool_of(q, pass)) vkCmdBeginQuery(cmd, p, 0, 0);
}

void end_gpu_stats(VkCommandBuffer cmd, const GpuStatsQueries& q, StatsPass pass) {
  if (VkQueryPool p = pool_of(q, pass)) vkCmdEndQuery(cmd, p, 0);
}

PipelineStats read_gpu_stats(vk::Context& ctx, const GpuStatsQueries& q, StatsPass pass) {
  PipelineStats s;
  VkQueryPool p = pool_of(q, pass);
  if (!p) return s;
  uint64_t v[kDrawCounters] = {};
  uint32_t n = pass == StatsPass::cull ? 1 : kDrawCounters;
  VK_CHECK(vkGetQueryPoolResults(ctx.device, p, 0, 1, n * sizeof(uint64_t), v, n * sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  s.available = true;
  if (pass == StatsPass::cull) {
    s.cs_invocations = v[0];
  } else {
    s.ia_vertices = v[0], s.ia_primitives = v[1], s.vs_invocations = v[2];
    s.clip_invocations = v[3], s.clip_primitives = v[4], s.fs_invocations = v[5];
  }
  return s;
}

}  // namespace forest
