// The impostor pass: far trees as one textured quad each (impostor.vert / impostor.frag,
// hemi-octahedral atlases baked by engine/tools/bake/impostor_bake.h). cull.comp appends the
// trees whose impostor is at least as good as their mesh (shaders/impostor_switch.glsl) to the
// camera's list, shadow_cull.comp to each cascade's; each list is one indirect draw of 6
// vertices per listed tree (DrawCounts.impostor_draws). The camera's quads face the camera
// and blend the three nearest views with depth parallax, lit like the leaves; the shadow
// map's face the sun, depth only.
#pragma once
#include <cstdint>

#include "engine/render/cull_pass.h"
#include "engine/render/descriptor_table.h"
#include "gpu_types.h"

namespace forest {

struct ImpostorPass {
  VkPipeline draw = VK_NULL_HANDLE;    // the draw pass's targets (its sample count)
  VkPipeline shadow = VK_NULL_HANDLE;  // the shadow map: depth only
  vk::Buffer list;                     // ImpostorEntry: IMPOSTOR_LISTS lists of instance_count
  uint32_t instance_count = 0;
};

inline constexpr Binding kImpostorBindings[] = {
    {BINDING_IMPOSTOR_LIST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT},
    {BINDING_IMPOSTOR_ALBEDO, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_IMPOSTOR_NORMALS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
};

ImpostorPass create_impostor_pass(vk::Context& ctx, VkPipelineLayout layout, uint32_t instance_count,
                                  VkSampleCountFlagBits samples);
void destroy_impostor_pass(vk::Context& ctx, ImpostorPass& pass);
void write_impostor_bindings(DescriptorWrites& writes, const ImpostorPass& pass);

// Draws list 0 (the camera, cascade SHADOW_NONE) or list 1 + c (cascade c) inside the
// caller's rendering, with set 0 bound to graphics; a cascade's with the depth-only pipeline.
void record_impostor_draw(VkCommandBuffer cmd, const ImpostorPass& pass, VkPipelineLayout layout, const CullPass& cull,
                          uint32_t cascade);

}  // namespace forest
