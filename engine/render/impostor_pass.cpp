#include "engine/render/impostor_pass.h"

#include <algorithm>
#include <cstddef>

#include "engine/render/render_targets.h"
#include "engine/render/shadow_pass.h"
#include "engine/vk/pipelines.h"

namespace forest {

ImpostorPass create_impostor_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count,
                                  VkSampleCountFlagBits samples) {
  ImpostorPass p;
  p.instance_count = instance_count;
  vk::GraphicsPipelineDesc d;
  d.vertex = "impostor_vert";
  d.fragment = "impostor_frag";
  d.vertex_input = false;
  d.cull = VK_CULL_MODE_NONE;
  d.color_format = kColorFormat;
  d.depth_format = kDepthFormat;
  d.samples = samples;
  p.draw = vk::create_graphics_pipeline(ctx, layout, d);
  // The shadow map's: depth only, its standard Z (shadow_pass.cpp). No depth bias: the
  // fragment shader writes the depth, which the rasterizer's bias never touches.
  vk::GraphicsPipelineDesc s = d;
  s.fragment = "impostor_shadow_frag";
  s.color_format = VK_FORMAT_UNDEFINED;
  s.depth_format = kShadowFormat;
  s.samples = VK_SAMPLE_COUNT_1_BIT;
  s.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  p.shadow = vk::create_graphics_pipeline(ctx, layout, s);
  p.list = vk::create_buffer(ctx, sizeof(gpu::ImpostorEntry) * IMPOSTOR_LISTS * std::max(instance_count, 1u),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::device);
  return p;
}

void destroy_impostor_pass(vk::Context& ctx, ImpostorPass& p) {
  vkDestroyPipeline(ctx.device, p.draw, nullptr);
  vkDestroyPipeline(ctx.device, p.shadow, nullptr);
  vk::destroy_buffer(ctx, p.list);
  p = {};
}

void write_impostor_bindings(DescriptorWrites& w, const ImpostorPass& p) { w.buffer(BINDING_IMPOSTOR_LIST, p.list); }

void record_impostor_draw(VkCommandBuffer cmd, const ImpostorPass& p, VkPipelineLayout layout, const CullPass& cull,
                          uint32_t cascade) {
  if (p.instance_count == 0) return;
  const bool shadow = cascade != SHADOW_NONE;
  gpu::DrawPush push{0, cascade};
  vkCmdPushConstants(cmd, layout, kDrawPushRange.stageFlags, kDrawPushRange.offset, sizeof(push), &push);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow ? p.shadow : p.draw);
  const uint32_t list = shadow ? 1 + cascade : 0;
  // The count variant with the list's instance count as its count (at most 1 draw): Mesa 22.3's
  // lavapipe drew nothing for a plain vkCmdDrawIndexedIndirect from a buffer the cull pass wrote
  // earlier in the same submission (measured; the count variants, as every other draw here, work).
  const VkDeviceSize at = offsetof(gpu::DrawCounts, impostor_draws) + sizeof(gpu::ImpostorDraw) * list;
  vkCmdDrawIndexedIndirectCount(cmd, cull.counts.buffer, at, cull.counts.buffer, at + offsetof(gpu::ImpostorDraw, instance_count), 1,
                                sizeof(gpu::ImpostorDraw));
}

}  // namespace forest
