// The sun's shadow pass: shadow_cull.comp appends, per cascade of shadow_cascades.h, the
// indirect draws of every tree whose sphere touches the cascade's caster volume (with the
// camera mode's λ and area scale: a pruned tree casts its pruned shadow), then each cascade's
// layer of the shadow map gets a depth-only render of the terrain (hills shadow trees), the
// bark and the alpha-tested leaf cards. tree.frag and terrain.frag sample it (shadow.glsl)
// with 3×3 bilinear PCF. Shadows never touch coverage (mask) frames.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/render/cull_pass.h"
#include "engine/render/descriptor_table.h"
#include "engine/render/impostor_pass.h"
#include "engine/render/scene_buffers.h"
#include "engine/render/terrain_cull.h"
#include "gpu_types.h"

namespace forest {

inline constexpr VkFormat kShadowFormat = VK_FORMAT_D32_SFLOAT;

struct ShadowPass {
  VkPipeline cull = VK_NULL_HANDLE;
  VkPipeline receivers = VK_NULL_HANDLE;  // receiver_mask.comp
  vk::Buffer receiver_mask;               // SHADOW_CASCADES × RECEIVER_MASK_WORDS bits
  VkPipeline terrain = VK_NULL_HANDLE, branches = VK_NULL_HANDLE;
  VkPipeline leaves = VK_NULL_HANDLE, leaves_instanced = VK_NULL_HANDLE;  // pulled / instanced (draw_pass.h)
  vk::Image map;  // SHADOW_CASCADES layers; map.view is the 2D-array view the shaders sample
  std::array<VkImageView, SHADOW_CASCADES> layers{};  // attachment views
  VkSampler sampler = VK_NULL_HANDLE;                 // depth compare (LESS_OR_EQUAL: lit), linear
  uint32_t resolution = 0;
  uint32_t instance_count = 0;
};

inline constexpr Binding kShadowBindings[] = {
    {BINDING_COMMANDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT},
    {BINDING_DRAW_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_SHADOW_MAP, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT},  // vertex: leaf_sun_shadow
    {BINDING_RECEIVER_MASK, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
};

// The draw push constants (vertex stage; impostors read the cascade in the fragment stage too), after PrCountPush's compute range.
inline constexpr VkPushConstantRange kDrawPushRange{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, DRAW_PUSH_OFFSET, sizeof(gpu::DrawPush)};

// The map starts in SHADER_READ_ONLY_OPTIMAL (lit everywhere), so frames without shadows can
// bind it.
ShadowPass create_shadow_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count, uint32_t resolution);
void destroy_shadow_pass(vk::Context& ctx, ShadowPass& pass);
void write_shadow_bindings(DescriptorWrites& writes, const ShadowPass& pass);

// The receiver mask of this frame from the previous frame's depth pyramid (level 0 of
// `pyramid_size` texels), for frames whose FrameData.receiver_mask is 1; set 0 bound to
// compute. Before: the pyramid written (the frame's opening barrier). After: the mask visible
// to shadow_cull.comp.
void record_receiver_mask(VkCommandBuffer cmd, const ShadowPass& pass, VkExtent2D pyramid_size);
// shadow_cull.comp (set 0 bound to compute; after record_cull_pass cleared the counts).
void record_shadow_cull(VkCommandBuffer cmd, const ShadowPass& pass);
// The depth renders of every cascade (set 0 bound to graphics by this call). Before: the
// shadow cull's writes visible to indirect and vertex reads. After: the map is in
// SHADER_READ_ONLY_OPTIMAL, its writes visible to fragment shaders.
void record_shadow_pass(VkCommandBuffer cmd, const ShadowPass& pass, VkPipelineLayout layout, VkDescriptorSet set,
                        const SceneBuffers& scene, const CullPass& cull, const ImpostorPass& impostors,
                        bool instanced_leaves, std::span<const std::vector<IndexRange>, SHADOW_CASCADES> terrain);

}  // namespace forest
