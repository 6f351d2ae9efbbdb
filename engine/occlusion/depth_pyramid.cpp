#include "engine/occlusion/depth_pyramid.h"

#include <algorithm>
#include <cstring>
#include <iterator>

#include "engine/vk/pipelines.h"
#include "gpu_types.h"

namespace forest {

namespace {

constexpr VkFormat kPyramidFormat = VK_FORMAT_R32_SFLOAT;

uint32_t previous_power_of_two(uint32_t v) {
  uint32_t p = 1;
  while (p * 2 <= v) p *= 2;
  return p;
}

VkExtent2D level_size(const DepthPyramid& p, uint32_t level) {
  return {std::max(p.size.width >> level, 1u), std::max(p.size.height >> level, 1u)};
}

VkSampler create_sampler(vk::Context& ctx, bool min_reduction) {
  VkSamplerReductionModeCreateInfo reduction{VK_STRUCTURE_TYPE_SAMPLER_REDUCTION_MODE_CREATE_INFO};
  reduction.reductionMode = VK_SAMPLER_REDUCTION_MODE_MIN;
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO, min_reduction ? &reduction : nullptr};
  sci.magFilter = sci.minFilter = min_reduction ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler;
  VK_CHECK(vkCreateSampler(ctx.device, &sci, nullptr, &sampler));
  return sampler;
}

VkPipeline create_pipeline(vk::Context& ctx, VkPipelineLayout layout, bool minmax) {
  VkShaderModule cs = vk::create_shader(ctx, "depth_pyramid_comp");
  uint32_t constant = minmax ? 1u : 0u;
  VkSpecializationMapEntry entry{SPEC_MINMAX_SAMPLER, 0, sizeof(uint32_t)};
  VkSpecializationInfo spec{1, &entry, sizeof(constant), &constant};
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, cs, "main",
              &spec};
  ci.layout = layout;
  VkPipeline pipeline;
  VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline));
  vkDestroyShaderModule(ctx.device, cs, nullptr);
  return pipeline;
}

}  // namespace

bool supports_minmax_reduction(vk::Context& ctx) {
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  vkGetPhysicalDeviceFeatures2(ctx.physical, &f);
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(ctx.physical, kPyramidFormat, &fp);
  return f12.samplerFilterMinmax && (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_MINMAX_BIT);
}

namespace {

// One descriptor set per level: the source (depth buffer or level above) -> the level.
void create_level_sets(vk::Context& ctx, DepthPyramid& p, VkImageView depth_view) {
  VkDescriptorSetLayoutCreateInfo slci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  slci.bindingCount = uint32_t(std::size(kPyramidSetBindings));
  slci.pBindings = kPyramidSetBindings;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &slci, nullptr, &p.set_layout));
  std::vector<VkDescriptorPoolSize> sizes;  // each binding of the table, once per level
  for (const VkDescriptorSetLayoutBinding& b : kPyramidSetBindings) sizes.push_back({b.descriptorType, p.levels});
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = p.levels;
  dpci.poolSizeCount = uint32_t(sizes.size());
  dpci.pPoolSizes = sizes.data();
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &dpci, nullptr, &p.pool));
  std::vector<VkDescriptorSetLayout> layouts(p.levels, p.set_layout);
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = p.pool;
  dsai.descriptorSetCount = p.levels;
  dsai.pSetLayouts = layouts.data();
  p.sets.resize(p.levels);
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &dsai, p.sets.data()));
  for (uint32_t i = 0; i < p.levels; ++i) {
    // Level 0 reads depth texels exactly (nearest); the others reduce the level above.
    VkDescriptorImageInfo source = i == 0 ? VkDescriptorImageInfo{p.point_sampler, depth_view,
                                                                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
                                          : VkDescriptorImageInfo{p.reduce_sampler, p.level_views[i - 1],
                                                                  VK_IMAGE_LAYOUT_GENERAL};
    VkDescriptorImageInfo destination{VK_NULL_HANDLE, p.level_views[i], VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    w[0].dstSet = w[1].dstSet = p.sets[i];
    w[0].dstBinding = PYRAMID_BINDING_SOURCE;
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w[0].pImageInfo = &source;
    w[1].dstBinding = PYRAMID_BINDING_DESTINATION;
    w[1].descriptorCount = 1;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w[1].pImageInfo = &destination;
    vkUpdateDescriptorSets(ctx.device, 2, w, 0, nullptr);
  }
}

// GENERAL for life, cleared to "infinitely far" (0): until a frame has been reduced into it
// the pyramid hides nothing.
void clear_to_far(vk::Context& ctx, const DepthPyramid& p) {
  vk::submit_now(ctx, [&](VkCommandBuffer cmd) {
    vk::image_barrier(cmd, p.image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                      VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT, p.levels);
    VkClearColorValue zero{};
    VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, p.levels, 0, 1};
    vkCmdClearColorImage(cmd, p.image.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                           VK_ACCESS_2_TRANSFER_READ_BIT);
  });
}

}  // namespace

DepthPyramid create_depth_pyramid(vk::Context& ctx, VkImageView depth_view, VkExtent2D depth_size, bool use_minmax) {
  DepthPyramid p;
  p.source_size = depth_size;
  p.size = {previous_power_of_two(depth_size.width), previous_power_of_two(depth_size.height)};
  p.levels = 1;
  while ((p.size.width >> p.levels) > 0 || (p.size.height >> p.levels) > 0) ++p.levels;
  p.minmax_sampler = use_minmax && supports_minmax_reduction(ctx);
  p.image = vk::create_mipmapped_image(
      ctx, p.size, kPyramidFormat,
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
          VK_IMAGE_USAGE_TRANSFER_DST_BIT,
      VK_IMAGE_ASPECT_COLOR_BIT, p.levels);
  for (uint32_t i = 0; i < p.levels; ++i) {
    VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vci.image = p.image.image;
    vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vci.format = kPyramidFormat;
    vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, i, 1, 0, 1};
    VkImageView view;
    VK_CHECK(vkCreateImageView(ctx.device, &vci, nullptr, &view));
    p.level_views.push_back(view);
  }
  p.reduce_sampler = create_sampler(ctx, p.minmax_sampler);
  p.point_sampler = create_sampler(ctx, false);

  create_level_sets(ctx, p, depth_view);
  p.layout = vk::create_pipeline_layout(ctx, p.set_layout, kPyramidPushRange);
  p.pipeline = create_pipeline(ctx, p.layout, p.minmax_sampler);

  clear_to_far(ctx, p);
  return p;
}

void destroy_depth_pyramid(vk::Context& ctx, DepthPyramid& p) {
  VkDevice dev = ctx.device;
  if (p.pipeline) vkDestroyPipeline(dev, p.pipeline, nullptr);
  if (p.layout) vkDestroyPipelineLayout(dev, p.layout, nullptr);
  if (p.pool) vkDestroyDescriptorPool(dev, p.pool, nullptr);
  if (p.set_layout) vkDestroyDescriptorSetLayout(dev, p.set_layout, nullptr);
  for (VkSampler s : {p.reduce_sampler, p.point_sampler})
    if (s) vkDestroySampler(dev, s, nullptr);
  for (VkImageView v : p.level_views) vkDestroyImageView(dev, v, nullptr);
  vk::destroy_image(ctx, p.image);
  p = {};
}

void record_depth_pyramid(VkCommandBuffer cmd, const DepthPyramid& p) {
  // The previous frame's reads (cull pass) and copies finish before the levels are rewritten.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
  for (uint32_t i = 0; i < p.levels; ++i) {
    VkExtent2D src = i == 0 ? p.source_size : level_size(p, i - 1), dst = level_size(p, i);
    gpu::DepthPyramidPush c{};
    c.source_size = {int32_t(src.width), int32_t(src.height)};
    c.destination_size = {int32_t(dst.width), int32_t(dst.height)};
    c.first_level = i == 0 ? 1u : 0u;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.sets[i], 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, kPyramidPushRange.stageFlags, 0, sizeof(c), &c);
    vkCmdDispatch(cmd, (dst.width + PYRAMID_GROUP_SIZE - 1) / PYRAMID_GROUP_SIZE,
                  (dst.height + PYRAMID_GROUP_SIZE - 1) / PYRAMID_GROUP_SIZE, 1);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  }
}

std::vector<std::vector<float>> read_depth_pyramid(vk::Context& ctx, const DepthPyramid& p) {
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize bytes = 0;
  for (uint32_t i = 0; i < p.levels; ++i) {
    VkExtent2D s = level_size(p, i);
    VkBufferImageCopy r{};
    r.bufferOffset = bytes;
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, i, 0, 1};
    r.imageExtent = {s.width, s.height, 1};
    regions.push_back(r);
    bytes += VkDeviceSize(s.width) * s.height * sizeof(float);
  }
  vk::Buffer readback = vk::create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  vk::submit_now(ctx, [&](VkCommandBuffer cmd) {
    vk::image_barrier(cmd, p.image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT, p.levels);
    vkCmdCopyImageToBuffer(cmd, p.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer,
                           uint32_t(regions.size()), regions.data());
    // Back to GENERAL for the next frame's passes.
    vk::image_barrier(cmd, p.image.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_NONE,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, p.levels);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  std::vector<std::vector<float>> levels;
  for (uint32_t i = 0; i < p.levels; ++i) {
    VkExtent2D s = level_size(p, i);
    levels.emplace_back(size_t(s.width) * s.height);
    std::memcpy(levels.back().data(), static_cast<const uint8_t*>(readback.mapped) + regions[i].bufferOffset,
                levels.back().size() * sizeof(float));
  }
  vk::destroy_buffer(ctx, readback);
  return levels;
}

}  // namespace forest
