// The renderer's one descriptor set layout, built from what each pass declares it binds
// (a pass lists its bindings next to its pipeline; adding a pass adds its list, nothing
// else). Bindings are written by binding number, checked against the table, never by
// position in an array; pool sizes are counted from the table.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "engine/vk/resources.h"

namespace forest {

// One binding of set 0: its number (BINDING_* in shaders/gpu_types.h), type and the stages
// that read it.
struct Binding {
  uint32_t binding;
  VkDescriptorType type;
  VkShaderStageFlags stages;
};

struct DescriptorTable {
  std::vector<Binding> bindings;  // the union of every pass's list, by binding number
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets;  // identical layouts: one per frame in flight
};

// The union of `lists`; one binding number declared twice must agree on its type (stages are
// merged). Throws vk::VkFailure on a conflict.
std::vector<Binding> merge_bindings(std::span<const std::span<const Binding>> lists);

DescriptorTable create_descriptor_table(vk::Context& ctx, std::span<const std::span<const Binding>> lists,
                                        uint32_t set_count);
void destroy_descriptor_table(vk::Context& ctx, DescriptorTable& table);

// Descriptor writes collected by binding number, applied to one set. apply() throws when a
// binding is not in the table, has another type, or (complete = true) when a binding of the
// table was left unwritten.
class DescriptorWrites {
 public:
  DescriptorWrites& buffer(uint32_t binding, const vk::Buffer& buffer);
  DescriptorWrites& image(uint32_t binding, VkSampler sampler, VkImageView view, VkImageLayout layout);
  void apply(vk::Context& ctx, const DescriptorTable& table, VkDescriptorSet set, bool complete) const;

 private:
  struct Write {
    uint32_t binding;
    bool is_image;
    VkDescriptorBufferInfo buffer;
    VkDescriptorImageInfo image;
  };
  std::vector<Write> writes_;
};

}  // namespace forest
