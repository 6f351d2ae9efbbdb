// Buffers and images with their own memory: the engine allocates a handful per scene,
// so one VkDeviceMemory per resource is simple and within every driver's limits.
#pragma once
#include <cstdint>
#include <span>

#include "engine/vk/context.h"

namespace forest::vk {

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers stay mapped
  VkDeviceSize allocated = 0;  // bytes of its memory (Context::memory_in_use)
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  VkDeviceSize allocated = 0;  // bytes of its memory (Context::memory_in_use)
};

enum class MemoryUse { device, upload, readback };

Buffer create_buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
void destroy_buffer(Context& ctx, Buffer& buffer);
// Device-local buffer filled from `data` through a staging buffer.
Buffer create_buffer_with_data(Context& ctx, VkBufferUsageFlags usage, std::span<const uint8_t> data);

template <typename T>
Buffer create_buffer_from(Context& ctx, VkBufferUsageFlags usage, std::span<const T> items) {
  return create_buffer_with_data(
      ctx, usage, {reinterpret_cast<const uint8_t*>(items.data()), items.size_bytes()});
}

Image create_image(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                   VkImageAspectFlags aspect, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
// Single-sample, `mips` levels; the view covers every level.
Image create_mipmapped_image(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                             VkImageAspectFlags aspect, uint32_t mips);
// Single-sample, one mip, `layers` layers; the view is a 2D array over all of them.
Image create_image_array(Context& ctx, VkExtent2D extent, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                         VkImageAspectFlags aspect);
// A 2D view of one layer (an attachment of a layered image); the caller destroys it.
VkImageView create_layer_view(Context& ctx, const Image& image, VkImageAspectFlags aspect, uint32_t layer);
void destroy_image(Context& ctx, Image& image);

// A sampled 2D array texture (square, all mips), filled from `texels`: layer-major, each
// layer its mip chain from level 0, tightly packed RGBA8.
Image create_texture_array(Context& ctx, uint32_t size, uint32_t layers, uint32_t mips, VkFormat format,
                           std::span<const uint8_t> texels);

// One synchronization2 image barrier (mips [0, levels), layers [0, layers)).
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                   VkImageLayout from, VkImageLayout to,
                   VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access, uint32_t levels = 1,
                   uint32_t layers = 1);
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access);

}  // namespace forest::vk
