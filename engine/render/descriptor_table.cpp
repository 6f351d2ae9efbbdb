#include "engine/render/descriptor_table.h"

#include <algorithm>
#include <map>
#include <string>

namespace forest {

std::vector<Binding> merge_bindings(std::span<const std::span<const Binding>> lists) {
  std::map<uint32_t, Binding> merged;
  for (std::span<const Binding> list : lists)
    for (const Binding& b : list) {
      auto [it, added] = merged.try_emplace(b.binding, b);
      if (added) continue;
      if (it->second.type != b.type)
        throw vk::VkFailure("descriptor binding " + std::to_string(b.binding) + " declared with two types");
      it->second.stages |= b.stages;
    }
  std::vector<Binding> out;
  for (auto& [number, b] : merged) out.push_back(b);
  return out;
}

DescriptorTable create_descriptor_table(vk::Context& ctx, std::span<const std::span<const Binding>> lists,
                                        uint32_t set_count) {
  DescriptorTable t;
  t.bindings = merge_bindings(lists);
  std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
  std::map<VkDescriptorType, uint32_t> counts;
  for (const Binding& b : t.bindings) {
    layout_bindings.push_back({b.binding, b.type, 1, b.stages, nullptr});
    counts[b.type] += set_count;
  }
  VkDescriptorSetLayoutCreateInfo slci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  slci.bindingCount = uint32_t(layout_bindings.size());
  slci.pBindings = layout_bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &slci, nullptr, &t.layout));
  std::vector<VkDescriptorPoolSize> sizes;
  for (auto [type, count] : counts) sizes.push_back({type, count});
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = set_count;
  dpci.poolSizeCount = uint32_t(sizes.size());
  dpci.pPoolSizes = sizes.data();
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &dpci, nullptr, &t.pool));
  std::vector<VkDescriptorSetLayout> layouts(set_count, t.layout);
  t.sets.resize(set_count);
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = t.pool;
  dsai.descriptorSetCount = set_count;
  dsai.pSetLayouts = layouts.data();
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &dsai, t.sets.data()));
  return t;
}

void destroy_descriptor_table(vk::Context& ctx, DescriptorTable& t) {
  vkDestroyDescriptorPool(ctx.device, t.pool, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, t.layout, nullptr);
  t = {};
}

DescriptorWrites& DescriptorWrites::buffer(uint32_t binding, const vk::Buffer& b) {
  writes_.push_back({binding, false, {b.buffer, 0, VK_WHOLE_SIZE}, {}});
  return *this;
}

DescriptorWrites& DescriptorWrites::image(uint32_t binding, VkSampler sampler, VkImageView view, VkImageLayout layout) {
  writes_.push_back({binding, true, {}, {sampler, view, layout}});
  return *this;
}

void DescriptorWrites::apply(vk::Context& ctx, const DescriptorTable& table, VkDescriptorSet set, bool complete) const {
  std::vector<VkWriteDescriptorSet> out;
  for (const Write& w : writes_) {
    auto it = std::find_if(table.bindings.begin(), table.bindings.end(),
                           [&](const Binding& b) { return b.binding == w.binding; });
    if (it == table.bindings.end())
      throw vk::VkFailure("descriptor write to binding " + std::to_string(w.binding) + ", which no pass declares");
    bool image_type = it->type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (image_type != w.is_image)
      throw vk::VkFailure("descriptor write of the wrong kind to binding " + std::to_string(w.binding));
    VkWriteDescriptorSet d{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    d.dstSet = set;
    d.dstBinding = w.binding;
    d.descriptorCount = 1;
    d.descriptorType = it->type;
    if (w.is_image)
      d.pImageInfo = &w.image;
    else
      d.pBufferInfo = &w.buffer;
    out.push_back(d);
  }
  if (complete)
    for (const Binding& b : table.bindings)
      if (std::none_of(writes_.begin(), writes_.end(), [&](const Write& w) { return w.binding == b.binding; }))
        throw vk::VkFailure("descriptor binding " + std::to_string(b.binding) + " left unwritten");
  vkUpdateDescriptorSets(ctx.device, uint32_t(out.size()), out.data(), 0, nullptr);
}

}  // namespace forest
