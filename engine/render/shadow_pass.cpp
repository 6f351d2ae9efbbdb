#include "engine/render/shadow_pass.h"

#include "engine/vk/pipelines.h"

namespace forest {

namespace {

// Slope-scaled bias against acne on surfaces at grazing sun angles; the receivers add a
// normal offset of about one texel (shadow.glsl), so this stays small.
constexpr float kBiasConstant = 1.0f, kBiasSlope = 1.5f;
// The stages that sample the map: fragments, and the leaf vertex shader (leaf_sun_shadow).
constexpr VkPipelineStageFlags2 kMapReaders = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

VkSampler create_compare_sampler(vk::Context& ctx) {
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;  // 2×2 PCF per tap
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  sci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;  // outside the map: lit
  sci.compareEnable = VK_TRUE;
  sci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;  // lit where the receiver is no deeper than the caster
  sci.maxLod = 0.0f;
  VkSampler s;
  VK_CHECK(vkCreateSampler(ctx.device, &sci, nullptr, &s));
  return s;
}

}  // namespace

ShadowPass create_shadow_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count, uint32_t resolution) {
  ShadowPass p;
  p.resolution = resolution;
  p.instance_count = instance_count;
  p.cull = vk::create_compute_pipeline(ctx, layout, "shadow_cull_comp");
  p.receivers = vk::create_compute_pipeline(ctx, layout, "receiver_mask_comp");
  p.receiver_mask = vk::create_buffer(ctx, sizeof(uint32_t) * SHADOW_CASCADES * RECEIVER_MASK_WORDS,
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      vk::MemoryUse::device);
  vk::GraphicsPipelineDesc d;
  d.depth_format = kShadowFormat;
  d.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;  // standard Z: 0 toward the sun
  d.cull = VK_CULL_MODE_NONE;  // the sun camera mirrors the winding; casters are thin anyway
  d.depth_bias_constant = kBiasConstant;
  d.depth_bias_slope = kBiasSlope;
  vk::GraphicsPipelineDesc terrain = d;
  terrain.vertex = "terrain_vert";
  p.terrain = vk::create_graphics_pipeline(ctx, layout, terrain);
  vk::GraphicsPipelineDesc branches = d;
  branches.vertex = "branch_vert";
  p.branches = vk::create_graphics_pipeline(ctx, layout, branches);
  vk::GraphicsPipelineDesc leaves = d;
  leaves.vertex = "leaf_caster_vert";      // no light, and no read of the map being drawn
  leaves.fragment = "shadow_leaf_frag";  // the card's alpha cut-out
  p.leaves_instanced = vk::create_graphics_pipeline(ctx, layout, leaves);
  if (vk::pull_leaves(ctx, leaves, "leaf_caster_pulled_vert")) p.leaves = vk::create_graphics_pipeline(ctx, layout, leaves);
  p.map = vk::create_image_array(ctx, {resolution, resolution}, SHADOW_CASCADES, kShadowFormat,
                                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 VK_IMAGE_ASPECT_DEPTH_BIT);
  for (uint32_t c = 0; c < SHADOW_CASCADES; ++c)
    p.layers[c] = vk::create_layer_view(ctx, p.map, VK_IMAGE_ASPECT_DEPTH_BIT, c);
  p.sampler = create_compare_sampler(ctx);
  vk::submit_now(ctx, [&](VkCommandBuffer cmd) {
    vk::image_barrier(cmd, p.map.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                      kMapReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 1, SHADOW_CASCADES);
  });
  return p;
}

void destroy_shadow_pass(vk::Context& ctx, ShadowPass& p) {
  vk::destroy_buffer(ctx, p.receiver_mask);
  for (VkPipeline pipeline : {p.cull, p.receivers, p.terrain, p.branches, p.leaves, p.leaves_instanced})
    vkDestroyPipeline(ctx.device, pipeline, nullptr);
  for (VkImageView v : p.layers) vkDestroyImageView(ctx.device, v, nullptr);
  vkDestroySampler(ctx.device, p.sampler, nullptr);
  vk::destroy_image(ctx, p.map);
  p = {};
}

void write_shadow_bindings(DescriptorWrites& w, const ShadowPass& p) {
  w.image(BINDING_SHADOW_MAP, p.sampler, p.map.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  w.buffer(BINDING_RECEIVER_MASK, p.receiver_mask);
}

void record_receiver_mask(VkCommandBuffer cmd, const ShadowPass& p, VkExtent2D pyramid_size) {
  vkCmdFillBuffer(cmd, p.receiver_mask.buffer, 0, VK_WHOLE_SIZE, 0);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.receivers);
  vkCmdDispatch(cmd, (pyramid_size.width + PYRAMID_GROUP_SIZE - 1) / PYRAMID_GROUP_SIZE,
                (pyramid_size.height + PYRAMID_GROUP_SIZE - 1) / PYRAMID_GROUP_SIZE, 1);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

void record_shadow_cull(VkCommandBuffer cmd, const ShadowPass& p) {
  if (p.instance_count == 0) return;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.cull);
  vkCmdDispatch(cmd, (p.instance_count + CULL_GROUP_SIZE - 1) / CULL_GROUP_SIZE, 1, 1);
}

void record_shadow_pass(VkCommandBuffer cmd, const ShadowPass& p, VkPipelineLayout layout, VkDescriptorSet set,
                        const SceneBuffers& scene, const CullPass& cull, const ImpostorPass& impostors,
                        bool instanced_leaves, std::span<const std::vector<IndexRange>, SHADOW_CASCADES> terrain) {
  const VkPipelineStageFlags2 tests = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  // After the previous frame's shading read the map.
  vk::image_barrier(cmd, p.map.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, kMapReaders,
                    VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, tests,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, 1,
                    SHADOW_CASCADES);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
  VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &scene.vertices.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, scene.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
  const uint32_t n = p.instance_count, stride = sizeof(gpu::DrawCommand);
  for (uint32_t c = 0; c < SHADOW_CASCADES; ++c) {
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = p.layers[c];
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {1.0f, 0};  // nothing: lit
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {p.resolution, p.resolution}};
    ri.layerCount = 1;
    ri.pDepthAttachment = &depth;
    vkCmdBeginRendering(cmd, &ri);
    VkViewport viewport{0.0f, 0.0f, float(p.resolution), float(p.resolution), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {p.resolution, p.resolution}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    const uint32_t base = n * (3 + 2 * c);
    gpu::DrawPush push{0, c};
    vkCmdPushConstants(cmd, layout, kDrawPushRange.stageFlags, kDrawPushRange.offset, sizeof(push), &push);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.terrain);
    for (const IndexRange& r : terrain[c]) vkCmdDrawIndexed(cmd, r.count, 1, r.first, 0, 0);
    if (n > 0) {
      push.command_base = base;
      vkCmdPushConstants(cmd, layout, kDrawPushRange.stageFlags, kDrawPushRange.offset, sizeof(push), &push);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.branches);
      vkCmdDrawIndexedIndirectCount(cmd, cull.commands.buffer, VkDeviceSize(base) * stride, cull.counts.buffer,
                                    offsetof(gpu::DrawCounts, shadow_branch_draws) + 4 * c, n, stride);
      push.command_base = base + n;
      vkCmdPushConstants(cmd, layout, kDrawPushRange.stageFlags, kDrawPushRange.offset, sizeof(push), &push);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, instanced_leaves ? p.leaves_instanced : p.leaves);
      vkCmdDrawIndexedIndirectCount(cmd, cull.commands.buffer, VkDeviceSize(base + n) * stride, cull.counts.buffer,
                                    offsetof(gpu::DrawCounts, shadow_leaf_draws) + 4 * c, n, stride);
      record_impostor_draw(cmd, impostors, layout, cull, c);
    }
    vkCmdEndRendering(cmd);
  }
  vk::image_barrier(cmd, p.map.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                    kMapReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 1, SHADOW_CASCADES);
}

}  // namespace forest
