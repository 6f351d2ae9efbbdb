#include "engine/render/scene_buffers.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "engine/occlusion/occlusion_samples.h"
#include "engine/render/bark_textures.h"
#include "engine/render/impostor_textures.h"
#include "engine/render/leaf_card.h"
#include "engine/render/leaf_textures.h"
#include "generators/asset/pr_tables.h"

#include <glm/gtc/packing.hpp>

namespace forest {

namespace {

struct SceneArrays {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<gpu::Model> models;
  std::vector<gpu::Leaf> leaves;
  std::vector<float> tables;
  std::vector<gpu::HullSample> hull_samples;

  // Appends a mesh to the global vertex/index arrays; returns (first index, vertex offset).
  std::pair<uint32_t, int32_t> append(const Mesh& mesh) {
    std::pair<uint32_t, int32_t> at{uint32_t(indices.size()), int32_t(vertices.size())};
    vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
    indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    return at;
  }
};

// Branch LOD chain: LOD0 then the simplified levels, at most MAX_BRANCH_LODS, errors
// non-decreasing.
void add_branch_lods(SceneArrays& a, const TreeModel& tm, gpu::Model& m) {
  std::vector<std::pair<const Mesh*, float>> lods{{&tm.branches, 0.0f}};
  for (const MeshLod& l : tm.branch_lods)
    if (lods.size() < MAX_BRANCH_LODS && !l.mesh.indices.empty())
      lods.push_back({&l.mesh, std::max(l.error, lods.back().second)});
  m.lod_count = uint32_t(lods.size());
  for (uint32_t k = 0; k < m.lod_count; ++k) {
    auto [first, offset] = a.append(*lods[k].first);
    m.lod_first_index[k] = first;
    m.lod_index_count[k] = uint32_t(lods[k].first->indices.size());
    m.lod_vertex_offset[k] = offset;
    m.lod_error[k] = lods[k].second;
  }
}

// The shared index pattern: one card quad (corners 0 1 2, 0 2 3; impostors draw it), then
// pulled leaf j's triangle 4j + (0 1 2) for `leaves` leaves (gpu_types.h, leaf_draw.glsl).
uint32_t append_quad_pattern(SceneArrays& a, uint32_t leaves) {
  const uint32_t first = uint32_t(a.indices.size());
  for (uint32_t c : {0u, 1u, 2u, 0u, 2u, 3u}) a.indices.push_back(c);
  for (uint32_t j = 0; j < leaves; ++j) a.indices.push_back(j);  // one point a leaf (leaf_card.geom)
  return first;
}

void add_foliage(SceneArrays& a, const TreeModel& tm, gpu::Model& m, bool& pullable) {
  // A quad card is drawn as its enclosing triangle (leaf_triangle), pulled or instanced alike;
  // any other card only as instances of its own mesh.
  glm::vec4 quad[4];
  Mesh card = tm.leaf_card;
  if (card_quad_corners(tm.leaf_card, quad)) {
    glm::vec4 tri[3];
    leaf_triangle(quad, tri);
    card.vertices.resize(3);
    card.indices = {0, 1, 2};
    for (int k = 0; k < 3; ++k) {
      m.card_corners[k] = tri[k];
      card.vertices[k].position = glm::vec3(tri[k].x, tri[k].y, 0.0f);
      card.vertices[k].normal = glm::vec3(0.0f, 0.0f, 1.0f);
      card.vertices[k].uv = glm::vec2(tri[k].z, tri[k].w);
    }
    m.card_corners[3] = glm::vec4(0.0f);
  } else if (!tm.leaves.empty() && !tm.leaf_card.indices.empty()) {
    pullable = false;
  }
  auto [cf, cv] = a.append(card);
  m.card_first_index = cf;
  m.card_index_count = uint32_t(card.indices.size());
  m.card_vertex_offset = cv;
  for (const Vertex& v : tm.leaf_card.vertices) m.card_radius = std::max(m.card_radius, glm::length(v.position));
  m.leaf_offset = uint32_t(a.leaves.size());
  m.leaf_count = tm.leaf_card.indices.empty() ? 0 : uint32_t(tm.leaves.size());
  // Crown depths (bake): one per leaf, checked on load; κ = 0 tells leaf.vert there are none.
  const std::optional<CrownLight>& crown = tm.bake.crown;
  if (crown && crown->depths.size() != tm.leaves.size())
    throw std::invalid_argument("upload_scene: " + std::to_string(crown->depths.size()) + " crown depths for " +
                                std::to_string(tm.leaves.size()) + " leaves");
  m.crown_extinction = crown ? crown->extinction : 0.0f;
  for (size_t i = 0; i < tm.leaves.size(); ++i) {
    const LeafPlacement& l = tm.leaves[i];
    glm::uvec4 depth(0u);
    if (crown) {
      const CrownCube& d = crown->depths[i];
      depth = glm::uvec4(glm::packHalf2x16({d[0], d[1]}), glm::packHalf2x16({d[2], d[3]}),
                         glm::packHalf2x16({d[4], d[5]}), 0u);
    }
    a.leaves.push_back({glm::vec4(l.position, l.scale), glm::vec4(l.rotation.x, l.rotation.y, l.rotation.z, l.rotation.w),
                        glm::vec4(l.color, 1.0f), depth});
  }
}

void add_bake_data(SceneArrays& a, const TreeModel& tm, gpu::Model& m) {
  if (const std::optional<PrTables>& t = tm.bake.pr_tables) {
    // Validated when the asset was read; sizes checked again here as they bound GPU reads.
    bool sized = t->sizes.size() == PR_SIZES;
    for (const PrSizeTables& b : t->sizes)
      sized = sized && b.s_opt.size() == S_SAMPLES && b.q_opt.size() == S_SAMPLES && b.lambda_opt.size() == D_SAMPLES &&
              b.s_far.size() == F_SAMPLES && b.q_far.size() == F_SAMPLES && b.q_low.size() == S_SAMPLES &&
              b.q_low_far.size() == F_SAMPLES;
    if (!sized) throw std::invalid_argument("upload_scene: PR tables of the wrong shape");
    m.has_tables = 1;
    m.table_offset = uint32_t(a.tables.size());
    m.pr_size0 = t->size0;
    for (const PrSizeTables& b : t->sizes) {  // one TABLE_BLOCK per size (gpu_types.h)
      a.tables.insert(a.tables.end(), b.s_opt.begin(), b.s_opt.end());
      a.tables.insert(a.tables.end(), b.q_opt.begin(), b.q_opt.end());
      a.tables.insert(a.tables.end(), b.lambda_opt.begin(), b.lambda_opt.end());
      a.tables.insert(a.tables.end(), b.s_far.begin(), b.s_far.end());
      a.tables.insert(a.tables.end(), b.q_far.begin(), b.q_far.end());
      a.tables.insert(a.tables.end(), b.q_low.begin(), b.q_low.end());
      a.tables.insert(a.tables.end(), b.q_low_far.begin(), b.q_low_far.end());
    }
  }
  OcclusionSamples occ = occlusion_samples(tm);
  m.sample_offset = uint32_t(a.hull_samples.size());
  m.sample_count = uint32_t(occ.samples.size());
  m.occlusion_margin = occ.margin;
  a.hull_samples.insert(a.hull_samples.end(), occ.samples.begin(), occ.samples.end());
}

// Trilinear; leaf cards clamp (their texture is one leaf), bark repeats (its tiles).
VkSampler create_trilinear_sampler(vk::Context& ctx, VkSamplerAddressMode address) {
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = VK_FILTER_LINEAR;
  sci.minFilter = VK_FILTER_LINEAR;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = address;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  VkSampler sampler = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSampler(ctx.device, &sci, nullptr, &sampler));
  return sampler;
}

// The leaf texture array (one layer per model) and the bark arrays (one layer per distinct
// bark; a textured model's colour is in its albedo, so its bark_color factor becomes white).
void upload_textures(vk::Context& ctx, const Scene& scene, std::vector<gpu::Model>& models, SceneBuffers& b) {
  std::vector<const Image8*> textures;
  std::vector<const TreeModel*> barks;
  for (const TreeModel& tm : scene.models) textures.push_back(&tm.leaf_texture), barks.push_back(&tm);
  TextureArrayData tex = build_leaf_texture_array(textures, LEAF_TEXTURE_SIZE);
  b.leaf_textures = vk::create_texture_array(ctx, tex.size, tex.layers, tex.mips, VK_FORMAT_R8G8B8A8_SRGB, tex.texels);
  b.leaf_sampler = create_trilinear_sampler(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  BarkTextureArrays bark = build_bark_texture_arrays(barks, BARK_TEXTURE_SIZE);
  for (size_t i = 0; i < models.size(); ++i) {
    models[i].bark_texture_layer = bark.layer[i];
    if (bark.coloured[i]) models[i].bark_color = glm::vec4(1.0f);
  }
  const TextureArrayData& al = bark.albedo;
  const TextureArrayData& nm = bark.normals;
  b.bark_albedo = vk::create_texture_array(ctx, al.size, al.layers, al.mips, VK_FORMAT_R8G8B8A8_SRGB, al.texels);
  b.bark_normals = vk::create_texture_array(ctx, nm.size, nm.layers, nm.mips, VK_FORMAT_R8G8B8A8_UNORM, nm.texels);
  b.bark_sampler = create_trilinear_sampler(ctx, VK_SAMPLER_ADDRESS_MODE_REPEAT);
  std::vector<const TreeModel*> all;
  for (const TreeModel& tm : scene.models) all.push_back(&tm);
  ImpostorArrays imp = build_impostor_arrays(all);
  for (size_t i = 0; i < models.size(); ++i) {
    models[i].impostor_layer = imp.layer[i];
    models[i].impostor_cutoff = scene.models[i].impostor.cutoff;
    const std::vector<float>& q = scene.models[i].impostor.q;
    // Unmeasured: never as good as a mesh (Q −1), except where IMPOSTORS_ALWAYS draws it.
    for (uint32_t k = 0; k < PR_SIZES; ++k) models[i].impostor_q[k] = q.size() == PR_SIZES ? q[k] : -1.0f;
  }
  const TextureArrayData& ia = imp.albedo;
  const TextureArrayData& in = imp.normals;
  b.impostor_albedo = vk::create_texture_array(ctx, ia.size, ia.layers, ia.mips, VK_FORMAT_R8G8B8A8_SRGB, ia.texels);
  b.impostor_normals = vk::create_texture_array(ctx, in.size, in.layers, in.mips, VK_FORMAT_R8G8B8A8_UNORM, in.texels);
  b.impostor_sampler = create_trilinear_sampler(ctx, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

}  // namespace

SceneBuffers upload_scene(vk::Context& ctx, const Scene& scene) {
  SceneBuffers b;
  SceneArrays a;
  Mesh terrain = scene.terrain.mesh();
  a.append(terrain);
  b.terrain_chunks = scene.terrain.chunks();
  for (const TreeModel& tm : scene.models) {
    gpu::Model m{};
    m.bounding_sphere = tm.bounding_sphere;
    m.bark_color = glm::vec4(tm.bark_color, 1.0f);
    m.leaf_color = glm::vec4(tm.leaf_color, 1.0f);
    m.leaf_texture_layer = uint32_t(a.models.size());
    add_branch_lods(a, tm, m);
    add_foliage(a, tm, m, b.leaves_pullable);
    add_bake_data(a, tm, m);
    a.models.push_back(m);
  }
  uint32_t most_leaves = 0;
  for (const gpu::Model& m : a.models) most_leaves = std::max(most_leaves, m.leaf_count);
  // At least one quad: impostors draw it too (impostor_pass.h).
  const uint32_t pattern = append_quad_pattern(a, b.leaves_pullable ? std::max(most_leaves, 1u) : 1u);
  for (gpu::Model& m : a.models) m.leaf_quad_first_index = pattern;
  b.instance_count = uint32_t(scene.instances.size());
  for (const gpu::Instance& inst : scene.instances) b.instance_leaves += scene.models[inst.model].leaves.size();

  upload_textures(ctx, scene, a.models, b);

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  b.vertices = vk::create_buffer_from<Vertex>(ctx, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, a.vertices);
  b.indices = vk::create_buffer_from<uint32_t>(ctx, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, a.indices);
  b.instances = vk::create_buffer_from<gpu::Instance>(ctx, storage, scene.instances);
  b.models = vk::create_buffer_from<gpu::Model>(ctx, storage, a.models);
  b.leaves = vk::create_buffer_from<gpu::Leaf>(ctx, storage, a.leaves);
  b.prune_tables = vk::create_buffer_from<float>(ctx, storage, a.tables);
  b.hull_samples = vk::create_buffer_from<gpu::HullSample>(ctx, storage, a.hull_samples);
  return b;
}

void destroy_scene_buffers(vk::Context& ctx, SceneBuffers& b) {
  for (vk::Buffer* buffer : {&b.vertices, &b.indices, &b.instances, &b.models, &b.leaves, &b.prune_tables, &b.hull_samples})
    vk::destroy_buffer(ctx, *buffer);
  for (vk::Image* image : {&b.leaf_textures, &b.bark_albedo, &b.bark_normals, &b.impostor_albedo, &b.impostor_normals})
    vk::destroy_image(ctx, *image);
  vkDestroySampler(ctx.device, b.leaf_sampler, nullptr);
  vkDestroySampler(ctx.device, b.impostor_sampler, nullptr);
  vkDestroySampler(ctx.device, b.bark_sampler, nullptr);
  b = {};
}

void write_scene_bindings(DescriptorWrites& w, const SceneBuffers& b) {
  w.buffer(BINDING_INSTANCES, b.instances)
      .buffer(BINDING_MODELS, b.models)
      .buffer(BINDING_LEAVES, b.leaves)
      .buffer(BINDING_PRUNE_TABLES, b.prune_tables)
      .buffer(BINDING_HULL_SAMPLES, b.hull_samples)
      .image(BINDING_LEAF_TEXTURES, b.leaf_sampler, b.leaf_textures.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .image(BINDING_BARK_ALBEDO, b.bark_sampler, b.bark_albedo.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .image(BINDING_BARK_NORMALS, b.bark_sampler, b.bark_normals.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .image(BINDING_IMPOSTOR_ALBEDO, b.impostor_sampler, b.impostor_albedo.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
      .image(BINDING_IMPOSTOR_NORMALS, b.impostor_sampler, b.impostor_normals.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

}  // namespace forest
