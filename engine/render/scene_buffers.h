// The scene on the GPU, uploaded once: one vertex and index buffer for the terrain and every
// model's branch LODs and leaf card, the instances, the models, their leaves in priority
// order, their PR tables, their occlusion samples, the leaf texture array and the bark
// texture arrays. Nothing here changes per frame; these are the bindings shaders/common.glsl
// declares for every stage.
#pragma once
#include <cstdint>

#include "engine/render/descriptor_table.h"
#include "engine/scene/scene.h"
#include "gpu_types.h"

namespace forest {

struct SceneBuffers {
  vk::Buffer vertices, indices;  // forest::Vertex, uint32 triangle lists
  vk::Buffer instances, models, leaves, prune_tables, hull_samples;
  vk::Image leaf_textures;  // one layer per model
  VkSampler leaf_sampler = VK_NULL_HANDLE;
  vk::Image bark_albedo, bark_normals;  // one layer per distinct bark, layer 0 neutral
  VkSampler bark_sampler = VK_NULL_HANDLE;  // repeat, trilinear
  vk::Image impostor_albedo, impostor_normals;  // impostor_textures.h: layer 0 empty
  VkSampler impostor_sampler = VK_NULL_HANDLE;  // clamp, trilinear
  uint32_t instance_count = 0;
  std::vector<TerrainChunk> terrain_chunks;  // the terrain, the first mesh of `indices`, by block
  uint64_t instance_leaves = 0;      // Σ over instances of its model's leaf count
  // Every model's leaf card is a quad, drawn as one triangle (Model::card_corners, leaf_card.h):
  // leaves may be drawn by vertex pulling (leaf_draw.glsl); else only as instances.
  bool leaves_pullable = true;
};

inline constexpr VkShaderStageFlags kAllStages =
    VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

// The frame constants (per frame in flight) and the scene's buffers: what every pass reads.
inline constexpr Binding kSceneBindings[] = {
    {BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAllStages},
    {BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages},
    {BINDING_MODELS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages},
    {BINDING_LEAVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages},
    {BINDING_PRUNE_TABLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kAllStages},
    {BINDING_HULL_SAMPLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
    {BINDING_LEAF_TEXTURES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_BARK_ALBEDO, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
    {BINDING_BARK_NORMALS, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
};

SceneBuffers upload_scene(vk::Context& ctx, const Scene& scene);
void destroy_scene_buffers(vk::Context& ctx, SceneBuffers& buffers);
// Every binding of kSceneBindings except BINDING_FRAME, and the impostor atlases.
void write_scene_bindings(DescriptorWrites& writes, const SceneBuffers& buffers);

}  // namespace forest
