#include "engine/vk/resources.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace forest::vk {

namespace {
uint32_t memory_type(const Context& ctx, uint32_t bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & want) == want) return i;
  throw VkFailure("no Vulkan memory type with the required properties");
}

// Refuses (VkFailure, exit code 1) a buffer the device cannot hold, before creating it:
// beyond maxBufferSize or maxMemoryAllocationSize creation is invalid usage, and beyond the
// largest heap the allocation fails anyway.
void check_buffer_size(const Context& ctx, VkDeviceSize size) {
  VkPhysicalDeviceMaintenance4Properties m4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
  VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  m3.pNext = &m4;
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  p2.pNext = &m3;
  vkGetPhysicalDeviceProperties2(ctx.physical, &p2);
  VkDeviceSize largest_heap = 0;
  for (uint32_t i = 0; i < ctx.memory.memoryHeapCount; ++i) largest_heap = std::max(largest_heap, ctx.memory.memoryHeaps[i].size);
  VkDeviceSize limit = std::min({m4.maxBufferSize, m3.maxMemoryAllocationSize, largest_heap});
  if (size > limit)
    throw VkFailure("out of GPU memory: a buffer of " + std::to_string(size >> 20) + " MiB exceeds the device's " +
                    std::to_string(limit >> 20) + " MiB limit (try a smaller scene)");
}
}  // namespace

Buffer create_buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use) {
  Buffer b;
  b.size = size;
  check_buffer_size(ctx, size);
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size > 0 ? size : 16;  // zero-sized buffers are invalid; keep empty scenes legal
  bci.usage = usage;
  bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(ctx.device, &bci, nullptr, &b.buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
  VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  if (use == MemoryUse::upload) want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  if (use == MemoryUse::readback)
    want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = memory_type(ctx, req.memoryTypeBits, want);
  if (VkResult r = vkAllocateMemory(ctx.device, &mai, nullptr, &b.memory); r != VK_SUCCESS) {
    vkDestroyBuffer(ctx.device, b.buffer, nullptr);  // reported, not leaked
    check(r, "vkAllocateMemory (buffer)");
  }
  VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
  b.allocated = req.size;
  ctx.memory_in_use += req.size;
  if (use != MemoryUse::device) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

void destroy_buffer(Context& ctx, Buffer& b) {
  if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(ctx.device, b.memory, nullptr);
  ctx.memory_in_use -= b.allocated;
  b = {};
}

Buffer create_buffer_with_data(Context& ctx, VkBufferUsageFlags usage, std::span<const uint8_t> data) {
  Buffer b = create_buffer(ctx, data.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::device);
  if (data.empty()) return b;
  Buffer staging = create_buffer(ctx, data.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::upload);
  std::memcpy(staging.mapped, data.data(), data.size());
  submit_now(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, data.size()};
    vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
  });
  destroy_buffer(ctx, staging);
  return b;
}

namespace {
// A device-local 2D image (array) with its own memory and a view of every mip and layer.
Image create_image_2d(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                      VkImageAspectFlags aspect, VkSampleCountFlagBits samples, uint32_t mips, uint32_t layers,
                      VkImageViewType view_type) {
  Image img;
  img.format = format;
  img.extent = extent;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {extent.width, extent.height, 1};
  ici.mipLevels = mips;
  ici.arrayLayers = layers;
  ici.samples = samples;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(ctx.device, &ici, nullptr, &img.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, img.image, &req);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = memory_type(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VK_CHECK(vkAllocateMemory(ctx.device, &mai, nullptr, &img.memory));
  VK_CHECK(vkBindImageMemory(ctx.device, img.image, img.memory, 0));
  img.allocated = req.size;
  ctx.memory_in_use += req.size;
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = img.image;
  vci.viewType = view_type;
  vci.format = format;
  vci.subresourceRange = {aspect, 0, mips, 0, layers};
  VK_CHECK(vkCreateImageView(ctx.device, &vci, nullptr, &img.view));
  return img;
}
}  // namespace

Image create_image(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                   VkImageAspectFlags aspect, VkSampleCountFlagBits samples) {
  return create_image_2d(ctx, extent, format, usage, aspect, samples, 1, 1, VK_IMAGE_VIEW_TYPE_2D);
}

Image create_image_array(Context& ctx, VkExtent2D extent, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                         VkImageAspectFlags aspect) {
  return create_image_2d(ctx, extent, format, usage, aspect, VK_SAMPLE_COUNT_1_BIT, 1, layers,
                         VK_IMAGE_VIEW_TYPE_2D_ARRAY);
}

VkImageView create_layer_view(Context& ctx, const Image& image, VkImageAspectFlags aspect, uint32_t layer) {
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = image.image;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = image.format;
  vci.subresourceRange = {aspect, 0, 1, layer, 1};
  VkImageView view;
  VK_CHECK(vkCreateImageView(ctx.device, &vci, nullptr, &view));
  return view;
}

Image create_mipmapped_image(Context& ctx, VkExtent2D extent, VkFormat format, VkImageUsageFlags usage,
                             VkImageAspectFlags aspect, uint32_t mips) {
  return create_image_2d(ctx, extent, format, usage, aspect, VK_SAMPLE_COUNT_1_BIT, mips, 1, VK_IMAGE_VIEW_TYPE_2D);
}

Image create_texture_array(Context& ctx, uint32_t size, uint32_t layers, uint32_t mips, VkFormat format,
                           std::span<const uint8_t> texels) {
  Image img = create_image_2d(ctx, {size, size}, format, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT, VK_SAMPLE_COUNT_1_BIT, mips, layers,
                              VK_IMAGE_VIEW_TYPE_2D_ARRAY);
  Buffer staging = create_buffer(ctx, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::upload);
  std::memcpy(staging.mapped, texels.data(), texels.size());
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (uint32_t layer = 0; layer < layers; ++layer)
    for (uint32_t mip = 0; mip < mips; ++mip) {
      uint32_t s = std::max(size >> mip, 1u);
      VkBufferImageCopy r{};
      r.bufferOffset = offset;
      r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, layer, 1};
      r.imageExtent = {s, s, 1};
      regions.push_back(r);
      offset += VkDeviceSize(s) * s * 4;
    }
  if (offset != texels.size()) throw VkFailure("texture array: texel data size does not match its mip chain");
  submit_now(ctx, [&](VkCommandBuffer cmd) {
    image_barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                  VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, mips, layers);
    vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           uint32_t(regions.size()), regions.data());
    image_barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, mips, layers);
  });
  destroy_buffer(ctx, staging);
  return img;
}

void destroy_image(Context& ctx, Image& img) {
  if (img.view) vkDestroyImageView(ctx.device, img.view, nullptr);
  if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
  if (img.memory) vkFreeMemory(ctx.device, img.memory, nullptr);
  ctx.memory_in_use -= img.allocated;
  img = {};
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from,
                   VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access, uint32_t levels,
                   uint32_t layers) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, levels, 0, layers};
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                    VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
  VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  b.srcStageMask = src_stage;
  b.srcAccessMask = src_access;
  b.dstStageMask = dst_stage;
  b.dstAccessMask = dst_access;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace forest::vk
