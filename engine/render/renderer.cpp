#include "engine/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "engine/render/leaf_textures.h"
#include "engine/occlusion/occlusion_samples.h"
#include "generators/asset/pr_tables.h"
#include "engine/vk/pipelines.h"

namespace forest {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr uint32_t kTimestampCount = 6;  // frame start, cull end, draw end, frame end, pyramid start/end
// Entries of the tail leaf buffer (64 MiB): forest5000's partly hidden trees need about 3 M.
constexpr uint32_t kTailCapacity = 1u << 24;
// A camera that moves or turns this much between two frames is a cut: the previous frame's
// depth says nothing about the new view, so occlusion treats every tree as visible.
constexpr float kCutDistance = 2.0f;    // meters
constexpr float kCutAngleDeg = 10.0f;

// Appends a mesh to the global vertex/index arrays; returns (first index, vertex offset).
std::pair<uint32_t, int32_t> append(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices, const Mesh& mesh) {
  std::pair<uint32_t, int32_t> at{uint32_t(indices.size()), int32_t(vertices.size())};
  vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
  indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
  return at;
}

}  // namespace

Renderer::Renderer(vk::Context& ctx, const Scene& scene, uint32_t width, uint32_t height, uint32_t samples)
    : ctx_(ctx), scene_(scene), width_(width), height_(height) {
  VkSampleCountFlags supported = ctx.properties.limits.framebufferColorSampleCounts &
                                 ctx.properties.limits.framebufferDepthSampleCounts;
  while (samples > 1 && !(supported & samples)) samples >>= 1;
  samples_ = VkSampleCountFlagBits(std::max(samples, 1u));

  // ---- geometry: one vertex and one index buffer for terrain and every model ----
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  Mesh terrain = scene.terrain.mesh();
  append(vertices, indices, terrain);
  terrain_index_count_ = uint32_t(terrain.indices.size());

  std::vector<gpu::Model> models;
  std::vector<gpu::Leaf> leaves;
  std::vector<float> tables;
  std::vector<gpu::HullSample> hull_samples;
  for (const TreeModel& tm : scene.models) {
    gpu::Model m{};
    m.bounding_sphere = tm.bounding_sphere;
    m.bark_color = glm::vec4(tm.bark_color, 1.0f);
    m.leaf_color = glm::vec4(tm.leaf_color, 1.0f);
    // Branch LOD chain: LOD0 then the simplified levels, at most MAX_BRANCH_LODS.
    std::vector<std::pair<const Mesh*, float>> lods{{&tm.branches, 0.0f}};
    for (const MeshLod& l : tm.branch_lods)
      if (lods.size() < MAX_BRANCH_LODS && !l.mesh.indices.empty()) lods.push_back({&l.mesh, std::max(l.error, lods.back().second)});
    m.lod_count = uint32_t(lods.size());
    for (uint32_t k = 0; k < m.lod_count; ++k) {
      auto [first, offset] = append(vertices, indices, *lods[k].first);
      m.lod_first_index[k] = first;
      m.lod_index_count[k] = uint32_t(lods[k].first->indices.size());
      m.lod_vertex_offset[k] = offset;
      m.lod_error[k] = lods[k].second;
    }
    m.leaf_texture_layer = uint32_t(models.size());
    if (auto t = read_pr_tables(tm.meta, tm.meta.value("species", "model"))) {
      m.has_tables = 1;
      m.table_offset = uint32_t(tables.size());
      tables.insert(tables.end(), t->s_opt.begin(), t->s_opt.end());
      tables.insert(tables.end(), t->lambda_opt.begin(), t->lambda_opt.end());
    }
    auto [cf, cv] = append(vertices, indices, tm.leaf_card);
    m.card_first_index = cf;
    m.card_index_count = uint32_t(tm.leaf_card.indices.size());
    m.card_vertex_offset = cv;
    for (const Vertex& v : tm.leaf_card.vertices) m.card_radius = std::max(m.card_radius, glm::length(v.position));
    m.leaf_offset = uint32_t(leaves.size());
    m.leaf_count = tm.leaf_card.indices.empty() ? 0 : uint32_t(tm.leaves.size());
    for (const LeafPlacement& l : tm.leaves)
      leaves.push_back({glm::vec4(l.position, l.scale), glm::vec4(l.rotation.x, l.rotation.y, l.rotation.z, l.rotation.w),
                        glm::vec4(l.color, 1.0f)});
    OcclusionSamples occ = occlusion_samples(tm);
    m.sample_offset = uint32_t(hull_samples.size());
    m.sample_count = uint32_t(occ.samples.size());
    m.occlusion_margin = occ.margin;
    hull_samples.insert(hull_samples.end(), occ.samples.begin(), occ.samples.end());
    models.push_back(m);
  }
  instance_count_ = uint32_t(scene.instances.size());

  std::vector<const Image8*> textures;
  for (const TreeModel& tm : scene.models) textures.push_back(&tm.leaf_texture);
  TextureArrayData tex = build_leaf_texture_array(textures, LEAF_TEXTURE_SIZE);
  leaf_textures_ = vk::create_texture_array(ctx, tex.size, tex.layers, tex.mips, VK_FORMAT_R8G8B8A8_SRGB, tex.texels);
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = VK_FILTER_LINEAR;
  sci.minFilter = VK_FILTER_LINEAR;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  VK_CHECK(vkCreateSampler(ctx.device, &sci, nullptr, &sampler_));

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  vertices_ = vk::create_buffer_from<Vertex>(ctx, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices);
  indices_ = vk::create_buffer_from<uint32_t>(ctx, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices);
  instances_ = vk::create_buffer_from<gpu::Instance>(ctx, storage, scene.instances);
  models_ = vk::create_buffer_from<gpu::Model>(ctx, storage, models);
  leaves_ = vk::create_buffer_from<gpu::Leaf>(ctx, storage, leaves);
  prune_tables_ = vk::create_buffer_from<float>(ctx, storage, tables);
  // TRANSFER_DST: coverage batches update it between the renders of one command buffer.
  frame_ = vk::create_buffer(ctx, sizeof(gpu::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             vk::MemoryUse::upload);
  // Room for one branch and two leaf commands (prefix, occlusion tail) per instance.
  commands_ = vk::create_buffer(ctx, sizeof(gpu::DrawCommand) * 3 * std::max(instance_count_, 1u),
                                storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT, vk::MemoryUse::device);
  counts_ = vk::create_buffer(ctx, sizeof(gpu::DrawCounts),
                              storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              vk::MemoryUse::device);
  counts_readback_ = vk::create_buffer(ctx, sizeof(gpu::DrawCounts), VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  image_readback_ = vk::create_buffer(ctx, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      vk::MemoryUse::readback);
  const VkDeviceSize frame_bytes = VkDeviceSize(width) * height * 4;
  coverage_reference_ = vk::create_buffer(ctx, frame_bytes, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
  coverage_test_ = vk::create_buffer(ctx, frame_bytes, storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::device);
  pr_counts_ = vk::create_buffer(ctx, sizeof(gpu::PrCounts),
                                 storage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 vk::MemoryUse::device);
  pr_readback_ = vk::create_buffer(ctx, sizeof(gpu::PrCounts), VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  // Sampled: forest walk's copy pass reads it when the window's format cannot be blitted to.
  color_ = vk::create_image(ctx, {width, height}, kColorFormat,
                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                            VK_IMAGE_ASPECT_COLOR_BIT);
  if (samples_ > VK_SAMPLE_COUNT_1_BIT)
    color_msaa_ = vk::create_image(ctx, {width, height}, kColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                   VK_IMAGE_ASPECT_COLOR_BIT, samples_);
  // Single-sampled depth feeds the depth pyramid directly; multisampled depth resolves (sample 0,
  // the one resolve mode every device has) into depth_resolve_ for it.
  const VkImageUsageFlags depth_usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  depth_ = vk::create_image(ctx, {width, height}, kDepthFormat,
                            depth_usage | (samples_ == VK_SAMPLE_COUNT_1_BIT ? VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT) : 0u),
                            VK_IMAGE_ASPECT_DEPTH_BIT, samples_);
  if (samples_ > VK_SAMPLE_COUNT_1_BIT)
    depth_resolve_ = vk::create_image(ctx, {width, height}, kDepthFormat, depth_usage | VK_IMAGE_USAGE_SAMPLED_BIT,
                                      VK_IMAGE_ASPECT_DEPTH_BIT);
  create_occlusion_resources(hull_samples);

  // ---- one descriptor set shared by every pipeline ----
  const VkShaderStageFlags all = VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  VkDescriptorSetLayoutBinding bindings[] = {
      {BINDING_FRAME, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, all, nullptr},
      {BINDING_INSTANCES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_MODELS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_LEAVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_COMMANDS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_DRAW_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_LEAF_TEXTURES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {BINDING_PRUNE_TABLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {BINDING_COVERAGE_REFERENCE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_COVERAGE_TEST, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_PR_COUNTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_DEPTH_PYRAMID, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_HULL_SAMPLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_INSTANCE_STATE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_TAIL_JOBS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {BINDING_TAIL_LEAVES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo slci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  slci.bindingCount = uint32_t(std::size(bindings));
  slci.pBindings = bindings;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &slci, nullptr, &set_layout_));
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 13},
                                  {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2}};
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = 1;
  dpci.poolSizeCount = 3;
  dpci.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &dpci, nullptr, &pool_));
  VkDescriptorSetAllocateInfo dsai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dsai.descriptorPool = pool_;
  dsai.descriptorSetCount = 1;
  dsai.pSetLayouts = &set_layout_;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &dsai, &set_));
  // Buffer bindings in the order of `bindings`, the image samplers (indices 6, 11) written below.
  const vk::Buffer* buffers[] = {&frame_,         &instances_,          &models_,        &leaves_,
                                 &commands_,      &counts_,             nullptr,         &prune_tables_,
                                 &coverage_reference_, &coverage_test_, &pr_counts_,     nullptr,
                                 &hull_samples_,  &instance_states_,   &tail_jobs_,     &tail_leaves_};
  const uint32_t binding_count = uint32_t(std::size(bindings));
  VkDescriptorBufferInfo infos[std::size(buffers)];
  VkWriteDescriptorSet writes[std::size(buffers)];
  for (uint32_t i = 0; i < binding_count; ++i) {
    if (!buffers[i]) continue;
    infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set_;
    writes[i].dstBinding = bindings[i].binding;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = bindings[i].descriptorType;
    writes[i].pBufferInfo = &infos[i];
  }
  VkDescriptorImageInfo image_info{sampler_, leaf_textures_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  writes[6] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  writes[6].dstSet = set_;
  writes[6].dstBinding = BINDING_LEAF_TEXTURES;
  writes[6].descriptorCount = 1;
  writes[6].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[6].pImageInfo = &image_info;
  VkDescriptorImageInfo pyramid_info{pyramid_sampler_, pyramid_.image.view, VK_IMAGE_LAYOUT_GENERAL};
  writes[11] = writes[6];
  writes[11].dstBinding = BINDING_DEPTH_PYRAMID;
  writes[11].pImageInfo = &pyramid_info;
  vkUpdateDescriptorSets(ctx.device, binding_count, writes, 0, nullptr);

  VkPipelineLayoutCreateInfo plci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  plci.setLayoutCount = 1;
  plci.pSetLayouts = &set_layout_;
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::PrCountPush)};
  plci.pushConstantRangeCount = 1;
  plci.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &plci, nullptr, &layout_));
  create_pipelines();

  VkQueryPoolCreateInfo qpci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qpci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qpci.queryCount = kTimestampCount;
  VK_CHECK(vkCreateQueryPool(ctx.device, &qpci, nullptr, &timestamps_));
  VkCommandBufferAllocateInfo cbai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cbai.commandPool = ctx.command_pool;
  cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cbai.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &cbai, &cmd_));
  pipeline_stats_ = create_gpu_stats(ctx);
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx.device, &fci, nullptr, &fence_));
}

void Renderer::create_pipelines() {
  cull_ = vk::create_compute_pipeline(ctx_, layout_, "cull_comp");
  tail_cull_ = vk::create_compute_pipeline(ctx_, layout_, "tail_cull_comp");
  pr_count_ = vk::create_compute_pipeline(ctx_, layout_, "pr_count_comp");
  vk::GraphicsPipelineDesc d;
  d.color_format = kColorFormat;
  d.depth_format = kDepthFormat;
  d.samples = samples_;
  vk::GraphicsPipelineDesc sky = d;
  sky.vertex = "sky_vert";
  sky.fragment = "sky_frag";
  sky.vertex_input = false;
  sky.cull = VK_CULL_MODE_NONE;
  sky.depth_test = false;
  sky.depth_write = false;
  sky_ = vk::create_graphics_pipeline(ctx_, layout_, sky);
  vk::GraphicsPipelineDesc terrain = d;
  terrain.vertex = "terrain_vert";
  terrain.fragment = "terrain_frag";
  terrain_ = vk::create_graphics_pipeline(ctx_, layout_, terrain);
  vk::GraphicsPipelineDesc branches = d;
  branches.vertex = "branch_vert";
  branches.fragment = "tree_frag";
  branches_ = vk::create_graphics_pipeline(ctx_, layout_, branches);
  vk::GraphicsPipelineDesc leaves = branches;
  leaves.vertex = "leaf_vert";
  leaves.cull = VK_CULL_MODE_NONE;  // leaf cards are two-sided
  leaves.alpha_to_coverage = samples_ > VK_SAMPLE_COUNT_1_BIT;
  leaves.fragment_constants = {1u, leaves.alpha_to_coverage ? 1u : 0u};  // LEAF, ALPHA_TO_COVERAGE
  // The leaf's (sharpened) alpha is coverage, not opacity: written to the attachment it made
  // the resolved frame translucent at every leaf edge, and a PNG viewer showed its page
  // background (white) through the crowns. The sky underneath already wrote alpha 1.
  leaves.write_alpha = false;
  leaves_pipeline_ = vk::create_graphics_pipeline(ctx_, layout_, leaves);
  if (ctx_.fill_mode_non_solid) {  // wireframe view: same shaders, edges only, no leaf alpha test
    terrain.polygon_mode = branches.polygon_mode = VK_POLYGON_MODE_LINE;
    terrain.cull = branches.cull = VK_CULL_MODE_NONE;
    terrain_wire_ = vk::create_graphics_pipeline(ctx_, layout_, terrain);
    branches_wire_ = vk::create_graphics_pipeline(ctx_, layout_, branches);
    vk::GraphicsPipelineDesc leaves_wire = branches;
    leaves_wire.vertex = "leaf_vert";
    leaves_wire_ = vk::create_graphics_pipeline(ctx_, layout_, leaves_wire);
  }
}

Renderer::~Renderer() {
  VkDevice dev = ctx_.device;
  vkDeviceWaitIdle(dev);
  vkDestroyFence(dev, fence_, nullptr);
  vkFreeCommandBuffers(dev, ctx_.command_pool, 1, &cmd_);
  vkDestroyQueryPool(dev, timestamps_, nullptr);
  destroy_gpu_stats(ctx_, pipeline_stats_);
  for (VkPipeline p : {cull_, tail_cull_, sky_, terrain_, branches_, leaves_pipeline_, pr_count_, terrain_wire_, branches_wire_, leaves_wire_})
    vkDestroyPipeline(dev, p, nullptr);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorPool(dev, pool_, nullptr);
  vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
  for (vk::Buffer* b : {&vertices_, &indices_, &instances_, &models_, &leaves_, &prune_tables_, &frame_, &commands_, &counts_,
                        &counts_readback_, &image_readback_, &coverage_reference_, &coverage_test_, &pr_counts_,
                        &pr_readback_})
    vk::destroy_buffer(ctx_, *b);
  vk::destroy_image(ctx_, color_);
  vk::destroy_image(ctx_, color_msaa_);
  vk::destroy_image(ctx_, leaf_textures_);
  vkDestroySampler(dev, sampler_, nullptr);
  vk::destroy_image(ctx_, depth_);
  vk::destroy_image(ctx_, depth_resolve_);
  vk::destroy_buffer(ctx_, hull_samples_);
  vk::destroy_buffer(ctx_, instance_states_);
  vk::destroy_buffer(ctx_, tail_jobs_);
  vk::destroy_buffer(ctx_, tail_leaves_);
  destroy_depth_pyramid(ctx_, pyramid_);
  vkDestroySampler(dev, pyramid_sampler_, nullptr);
}

void Renderer::create_occlusion_resources(const std::vector<gpu::HullSample>& samples) {
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  hull_samples_ = vk::create_buffer_from<gpu::HullSample>(ctx_, storage, samples);
  // Every instance starts fully visible, so the first frames draw exactly what the mode says.
  std::vector<gpu::InstanceState> states(std::max(instance_count_, 1u), gpu::InstanceState{1.0f, 1.0f, 0u, 0u});
  instance_states_ = vk::create_buffer_from<gpu::InstanceState>(ctx_, storage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, states);
  // Per-leaf occlusion of partly hidden trees (tail_cull.comp): at most one job per instance,
  // and room for every leaf of every instance up to kTailCapacity; a tree that finds no room
  // left draws its whole prefix.
  tail_jobs_ = vk::create_buffer(ctx_, sizeof(gpu::TailJob) * std::max(instance_count_, 1u), storage, vk::MemoryUse::device);
  uint64_t all_leaves = 0;
  for (const gpu::Instance& inst : scene_.instances) all_leaves += scene_.models[inst.model].leaves.size();
  tail_capacity_ = uint32_t(std::clamp<uint64_t>(all_leaves, 1, kTailCapacity));
  tail_leaves_ = vk::create_buffer(ctx_, sizeof(uint32_t) * tail_capacity_, storage, vk::MemoryUse::device);
  VkImageView source = depth_resolve_.image ? depth_resolve_.view : depth_.view;
  pyramid_ = create_depth_pyramid(ctx_, source, {width_, height_}, true);
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  sci.maxLod = VK_LOD_CLAMP_NONE;
  VK_CHECK(vkCreateSampler(ctx_.device, &sci, nullptr, &pyramid_sampler_));
}

void Renderer::record_pyramid(VkCommandBuffer cmd) {
  // The finished depth (or its resolve) becomes the pyramid's source.
  const vk::Image& source = depth_resolve_.image ? depth_resolve_ : depth_;
  vk::image_barrier(cmd, source.image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  record_depth_pyramid(cmd, pyramid_);
}

bool Renderer::camera_cut(const CameraMatrices& cm, const CameraDesc& camera, const FrameSettings& settings) const {
  if (settings.camera_cut || !pyramid_valid_) return true;
  if (camera.fov_deg != pyramid_camera_.fov_deg || camera.near != pyramid_camera_.near) return true;
  if (glm::distance(cm.position, pyramid_camera_.position) > kCutDistance) return true;
  glm::vec3 before = glm::normalize(pyramid_camera_.target - pyramid_camera_.position);
  return glm::dot(before, cm.forward) < std::cos(glm::radians(kCutAngleDeg));
}

std::vector<gpu::InstanceState> Renderer::instance_states() {
  std::vector<gpu::InstanceState> out(instance_count_);
  if (out.empty()) return out;
  VkDeviceSize bytes = sizeof(gpu::InstanceState) * out.size();
  vk::Buffer readback = vk::create_buffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  vk::submit_now(ctx_, [&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, bytes};
    vkCmdCopyBuffer(cmd, instance_states_.buffer, readback.buffer, 1, &copy);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  std::memcpy(out.data(), readback.mapped, bytes);
  vk::destroy_buffer(ctx_, readback);
  return out;
}

void Renderer::record(VkCommandBuffer cmd, Output output, bool mask, bool build_pyramid) {
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  vkCmdResetQueryPool(cmd, timestamps_, 0, kTimestampCount);
  reset_gpu_stats(cmd, pipeline_stats_);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, timestamps_, 0);

  // ---- cull: compacted indirect draws ----
  vkCmdFillBuffer(cmd, counts_.buffer, 0, sizeof(gpu::DrawCounts), 0);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  begin_gpu_stats(cmd, pipeline_stats_, StatsPass::cull);
  if (instance_count_ > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_);
    vkCmdDispatch(cmd, (instance_count_ + CULL_GROUP_SIZE - 1) / CULL_GROUP_SIZE, 1, 1);
  }
  if (instance_count_ > 0 && build_pyramid) {  // occlusion on: the tails of partly hidden trees
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                           VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, tail_cull_);
    vkCmdDispatchIndirect(cmd, counts_.buffer, offsetof(gpu::DrawCounts, tail_jobs));
  }
  end_gpu_stats(cmd, pipeline_stats_, StatsPass::cull);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                         VK_ACCESS_2_TRANSFER_READ_BIT);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, timestamps_, 1);

  // ---- draw: sky, terrain, branches, leaves ----
  vk::image_barrier(cmd, color_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  if (color_msaa_.image)
    vk::image_barrier(cmd, color_msaa_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  // Also after the previous frame's pyramid reads of the depth (compute).
  for (VkImage image : {depth_.image, depth_resolve_.image})
    if (image)
      vk::image_barrier(cmd, image, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                        VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                            VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);

  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = color_.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = mask ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // else the sky covers all
  color.clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};  // opaque: leaves write no alpha (see leaves.write_alpha)
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  if (color_msaa_.image) {  // render multisampled, resolve (average) into the single-sample image
    color.imageView = color_msaa_.view;
    color.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    color.resolveImageView = color_.view;
    color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_.view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  // Kept when the depth pyramid reads it (single-sampled) or resolved into depth_resolve_.
  depth.storeOp = build_pyramid && !depth_resolve_.image ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 is infinitely far
  if (depth_resolve_.image) {
    depth.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
    depth.resolveImageView = depth_resolve_.view;
    depth.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  }
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {width_, height_}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &color;
  ri.pDepthAttachment = &depth;
  begin_gpu_stats(cmd, pipeline_stats_, StatsPass::draw);
  vkCmdBeginRendering(cmd, &ri);
  VkViewport viewport{0.0f, 0.0f, float(width_), float(height_), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, {width_, height_}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);

  VkDeviceSize zero = 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vertices_.buffer, &zero);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  if (!mask) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sky_);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, wireframe_ ? terrain_wire_ : terrain_);
    vkCmdDrawIndexed(cmd, terrain_index_count_, 1, 0, 0, 0);
  }

  if (instance_count_ > 0) {
    const uint32_t stride = sizeof(gpu::DrawCommand);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, wireframe_ ? branches_wire_ : branches_);
    vkCmdDrawIndexedIndirectCount(cmd, commands_.buffer, 0, counts_.buffer, offsetof(gpu::DrawCounts, branch_draws),
                                  instance_count_, stride);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, wireframe_ ? leaves_wire_ : leaves_pipeline_);
    vkCmdDrawIndexedIndirectCount(cmd, commands_.buffer, VkDeviceSize(instance_count_) * stride, counts_.buffer,
                                  offsetof(gpu::DrawCounts, leaf_draws), 2 * instance_count_, stride);
  }
  vkCmdEndRendering(cmd);
  end_gpu_stats(cmd, pipeline_stats_, StatsPass::draw);
  color_layout_ = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, timestamps_, 2);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, timestamps_, 4);
  if (build_pyramid) record_pyramid(cmd);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, timestamps_, 5);

  // ---- readback: statistics always, pixels when asked ----
  VkBufferCopy counts_copy{0, 0, sizeof(gpu::DrawCounts)};
  vkCmdCopyBuffer(cmd, counts_.buffer, counts_readback_.buffer, 1, &counts_copy);
  if (output != Output::none) {
    vk::image_barrier(cmd, color_.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    VkBuffer target = output == Output::image       ? image_readback_.buffer
                      : output == Output::reference ? coverage_reference_.buffer
                                                    : coverage_test_.buffer;
    vkCmdCopyImageToBuffer(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, 1, &region);
    color_layout_ = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  }
  if (output == Output::compare) {
    vkCmdFillBuffer(cmd, pr_counts_.buffer, 0, sizeof(gpu::PrCounts), 0);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    record_pr_count(cmd, {width_ * height_, 0, PR_NO_MASK, 0});
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferCopy copy{0, 0, sizeof(gpu::PrCounts)};
    vkCmdCopyBuffer(cmd, pr_counts_.buffer, pr_readback_.buffer, 1, &copy);
  }
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, timestamps_, 3);
  VK_CHECK(vkEndCommandBuffer(cmd));
}

FrameSettings scene_frame_settings(const SceneDesc& desc) {
  FrameSettings s;
  s.prune_mode = desc.prune_mode;
  s.lambda_view = desc.lambda_view;
  s.mask = desc.mask_view;
  s.occlusion = desc.occlusion;
  return s;
}

FrameStats Renderer::render(const CameraDesc& camera, FrameImage* image) {
  return render(camera, image, scene_frame_settings(scene_.desc));
}

double PrResult::quality() const {
  double p = precision(), r = recall();
  return 1.0 - std::sqrt((1.0 - p) * (1.0 - p) + (1.0 - r) * (1.0 - r));
}

FrameStats Renderer::render(const CameraDesc& camera, FrameImage* image, const FrameSettings& settings) {
  FrameStats stats = submit(camera, settings, image ? Output::image : Output::none);
  if (image) {
    image->width = width_;
    image->height = height_;
    image->rgba.resize(size_t(width_) * height_ * 4);
    std::memcpy(image->rgba.data(), image_readback_.mapped, image->rgba.size());
  }
  return stats;
}

void Renderer::render_reference(const CameraDesc& camera, const FrameSettings& reference) {
  FrameSettings s = reference;
  s.mask = true;
  submit(camera, s, Output::reference);
}

PrResult Renderer::compare_with_reference(const CameraDesc& camera, const FrameSettings& test) {
  FrameSettings s = test;
  s.mask = true;
  submit(camera, s, Output::compare);
  gpu::PrCounts c;
  std::memcpy(&c, pr_readback_.mapped, sizeof(c));
  return {c.tp, c.fp, c.fn};
}

gpu::FrameData Renderer::frame_data(const CameraDesc& camera, const FrameSettings& settings) const {
  CameraMatrices cm = camera_matrices(camera, float(width_) / float(height_));
  const SkyDesc& sky = scene_.desc.sky;
  gpu::FrameData fd{};
  fd.view_proj = cm.view_proj;
  fd.inv_view_proj = glm::inverse(cm.view_proj);
  fd.camera_pos = glm::vec4(cm.position, 1.0f);
  fd.sun_dir = glm::vec4(sky.sun_direction, sky.sun_intensity);
  fd.sky_zenith = glm::vec4(sky.zenith, 1.0f);
  fd.sky_horizon = glm::vec4(sky.horizon, 1.0f);
  fd.fog = glm::vec4(sky.horizon, sky.fog_density);
  for (size_t i = 0; i < 6; ++i) fd.frustum[i] = cm.frustum[i];
  float pixels_per_meter = float(height_) / (2.0f * std::tan(glm::radians(camera.fov_deg) * 0.5f));
  fd.lod = glm::vec4(pixels_per_meter, scene_.desc.lod_error_pixels, 0.0f, 0.0f);
  fd.prune = glm::vec4(scene_.desc.prune_distance, scene_.desc.transition, settings.fixed_lambda, settings.fixed_scale);
  fd.lod_camera = glm::vec4(settings.lod_camera ? *settings.lod_camera : cm.position, 1.0f);
  fd.prune_mode = settings.prune_mode;
  fd.view_flags = (settings.lambda_view ? VIEW_LAMBDA : 0u) | (settings.mask ? VIEW_MASK : 0u);
  fd.instance_count = instance_count_;
  fd.leaf_command_base = instance_count_;
  fd.tail_capacity = tail_capacity_;
  // tail_cull.comp runs one workgroup per job, dispatched indirectly: never more than the
  // device's group count (65535 guaranteed; a scene may hold 1 M trees).
  fd.tail_job_capacity = std::min(instance_count_, ctx_.properties.limits.maxComputeWorkGroupCount[0]);
  return fd;
}

void Renderer::record_pr_count(VkCommandBuffer cmd, const gpu::PrCountPush& push) {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pr_count_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, (push.pixel_count + PR_GROUP_SIZE - 1) / PR_GROUP_SIZE, 1, 1);
}

double Renderer::submit_and_wait() {
  auto cpu_start = std::chrono::steady_clock::now();
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = cmd_;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  VK_CHECK(vkResetFences(ctx_.device, 1, &fence_));
  VK_CHECK(vkQueueSubmit2(ctx_.queue, 1, &si, fence_));
  double cpu_submit_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
  VK_CHECK(vkWaitForFences(ctx_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
  return cpu_submit_ms;
}

FrameStats Renderer::submit(const CameraDesc& camera, const FrameSettings& settings, Output output) {
  auto cpu_start = std::chrono::steady_clock::now();
  gpu::FrameData fd = frame_data(camera, settings);
  CameraMatrices cm = camera_matrices(camera, float(width_) / float(height_));
  const bool cut = settings.occlusion && camera_cut(cm, camera, settings);
  if (settings.occlusion) {
    fd.occlusion = OCCLUSION_ON | (cut ? OCCLUSION_CUT : 0u);
    fd.prev_view_proj = pyramid_view_proj_;
    fd.prev_camera = glm::vec4(pyramid_camera_.position, pyramid_camera_.near);
    fd.pyramid = glm::vec4(float(pyramid_.size.width), float(pyramid_.size.height), float(pyramid_.levels), 0.0f);
  }
  std::memcpy(frame_.mapped, &fd, sizeof(fd));

  VK_CHECK(vkResetCommandBuffer(cmd_, 0));
  wireframe_ = settings.wireframe && has_wireframe() && !settings.mask;
  record(cmd_, output, settings.mask, settings.occlusion);
  // The pyramid now holds this frame (or nothing usable, without occlusion).
  pyramid_valid_ = settings.occlusion;
  pyramid_view_proj_ = cm.view_proj;
  pyramid_camera_ = camera;
  double cpu_record_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
  double cpu_submit_ms = cpu_record_ms + submit_and_wait();

  FrameStats stats;
  stats.instances = instance_count_;
  gpu::DrawCounts counts;
  std::memcpy(&counts, counts_readback_.mapped, sizeof(counts));
  stats.branch_draws = counts.branch_draws;
  stats.leaf_draws = counts.leaf_draws;
  stats.leaves_drawn = counts.leaves_drawn;
  stats.branch_triangles = counts.branch_triangles;
  for (int k = 0; k < MAX_BRANCH_LODS; ++k) stats.lod_draws[k] = counts.lod_draws[k];
  stats.mean_lambda = counts.branch_draws ? double(counts.lambda_sum) / 4096.0 / counts.branch_draws : 0.0;
  stats.occluded_instances = counts.occluded_instances;
  stats.leaves_saved = counts.leaves_saved;
  stats.triangles_saved = counts.triangles_saved;
  stats.camera_cut = cut;
  uint64_t ts[kTimestampCount] = {};
  VK_CHECK(vkGetQueryPoolResults(ctx_.device, timestamps_, 0, kTimestampCount, sizeof(ts), ts, sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  double period_ms = double(ctx_.properties.limits.timestampPeriod) * 1e-6;
  stats.cull_ms = double(ts[1] - ts[0]) * period_ms;
  stats.draw_ms = double(ts[2] - ts[1]) * period_ms;
  stats.frame_ms = double(ts[3] - ts[0]) * period_ms;
  stats.pyramid_ms = double(ts[5] - ts[4]) * period_ms;
  stats.cpu_submit_ms = cpu_submit_ms;
  stats.cull_pipeline = read_gpu_stats(ctx_, pipeline_stats_, StatsPass::cull);
  stats.draw_pipeline = read_gpu_stats(ctx_, pipeline_stats_, StatsPass::draw);
  return stats;
}

}  // namespace forest
