// Depth pyramid (hierarchical Z) of a finished depth buffer, for the occlusion feedback of
// Neubert 2012 §7.4: a mip chain of R32F images whose texels hold the FARTHEST depth of the area
// they cover. The engine uses reversed Z (1 near, 0 infinitely far), so farthest = minimum.
// Level 0 is the largest power of two not above the depth buffer in each axis (so every
// further level halves exactly), built by shaders/depth_pyramid.comp.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/vk/resources.h"
#include "gpu_types.h"

namespace forest {

// depth_pyramid.comp's set (one per level) and push constants; tests/unit/test_gpu_interface.cpp
// checks the compiled shader against them.
inline constexpr VkDescriptorSetLayoutBinding kPyramidSetBindings[] = {
    {PYRAMID_BINDING_SOURCE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
    {PYRAMID_BINDING_DESTINATION, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
};
inline constexpr VkPushConstantRange kPyramidPushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::DepthPyramidPush)};

struct DepthPyramid {
  vk::Image image;                   // R32_SFLOAT, `levels` mips, always in VK_IMAGE_LAYOUT_GENERAL
  std::vector<VkImageView> level_views;
  VkExtent2D size{};                 // level 0
  uint32_t levels = 0;
  VkExtent2D source_size{};          // the depth buffer
  bool minmax_sampler = false;       // levels >= 1 reduce with a MIN sampler (else 4 fetches)
  VkSampler reduce_sampler = VK_NULL_HANDLE;  // MIN reduction (minmax) or plain nearest
  VkSampler point_sampler = VK_NULL_HANDLE;   // nearest, no reduction: depth reads, cull pass
  VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets;  // one per level: source view -> level view
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
};

// Whether the device can reduce R32_SFLOAT with a MIN sampler (samplerFilterMinmax and the
// format's SAMPLED_IMAGE_FILTER_MINMAX feature).
bool supports_minmax_reduction(vk::Context& ctx);

// `depth_view`: a single-sample depth image with VK_IMAGE_USAGE_SAMPLED_BIT, in
// VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL whenever the pyramid is built. `use_minmax` is
// honored only where supported.
DepthPyramid create_depth_pyramid(vk::Context& ctx, VkImageView depth_view, VkExtent2D depth_size, bool use_minmax);
void destroy_depth_pyramid(vk::Context& ctx, DepthPyramid& pyramid);

// Records the reduction of every level. Before: the depth writes are made visible to compute
// reads by the caller. After: every level is visible to compute-shader reads.
void record_depth_pyramid(VkCommandBuffer cmd, const DepthPyramid& pyramid);

// Reads every level back (tests): levels[i] is row-major, (size.width >> i) x (size.height >> i),
// at least 1 texel per axis.
std::vector<std::vector<float>> read_depth_pyramid(vk::Context& ctx, const DepthPyramid& pyramid);

}  // namespace forest
