// The images a frame is drawn into: the single-sampled sRGB colour image (what PNGs and the
// walk window get), and when multisampled, the MSAA colour it resolves from; the depth
// buffer, and when multisampled, its sample-0 resolve, the depth pyramid's source.
#pragma once
#include <cstdint>

#include "engine/vk/resources.h"

namespace forest {

inline constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

struct RenderTargets {
  VkExtent2D extent{};
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  vk::Image color;          // resolved, sampled (walk's copy pass) and copied from
  vk::Image color_msaa;     // only when samples > 1
  vk::Image depth;          // sampled when single-sampled: the pyramid's source
  vk::Image depth_resolve;  // only when samples > 1: sample 0 of depth, the pyramid's source
  const vk::Image& pyramid_source() const { return depth_resolve.image ? depth_resolve : depth; }
};

// `samples` is lowered to what the device supports for colour and depth.
RenderTargets create_render_targets(vk::Context& ctx, VkExtent2D extent, uint32_t samples);
void destroy_render_targets(vk::Context& ctx, RenderTargets& targets);

}  // namespace forest
