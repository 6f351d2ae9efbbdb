#include "engine/render/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>

#include "engine/vk/pipelines.h"

namespace forest {

namespace {

// Timestamps of one frame: start, cull end, draw end, frame end, pyramid start / end.
enum Timestamp : uint32_t {
  kFrameStart, kCullEnd, kDrawEnd, kFrameEnd, kPyramidStart, kPyramidEnd, kShadowStart, kShadowEnd, kTimestampCount
};
// A camera that moves or turns this much between two frames is a cut: the previous frame's
// depth says nothing about the new view, so occlusion treats every tree as visible.
constexpr float kCutDistance = 2.0f;  // meters
constexpr float kCutAngleDeg = 10.0f;

// Everything that may cast a shadow: the terrain square and the trees' spheres.
ShadowBounds scene_shadow_bounds(const Scene& scene) {
  const Terrain& t = scene.terrain;
  float half = t.desc.size * 0.5f;
  float lo = 0.0f, hi = 0.0f;
  if (!t.heights.empty()) {
    lo = *std::min_element(t.heights.begin(), t.heights.end());
    hi = *std::max_element(t.heights.begin(), t.heights.end());
  }
  ShadowBounds b{{-half, lo, -half}, {half, hi, half}};
  for (const gpu::Instance& inst : scene.instances) {
    const TreeModel& m = scene.models[inst.model];
    glm::vec3 p(inst.position_scale);
    float r = glm::length(glm::vec3(m.bounding_sphere)) + m.bounding_sphere.w;
    r *= inst.position_scale.w;
    b.min = glm::min(b.min, p - glm::vec3(r));
    b.max = glm::max(b.max, p + glm::vec3(r));
  }
  return b;
}

}  // namespace

Renderer::Renderer(vk::Context& ctx, const Scene& scene, uint32_t width, uint32_t height, uint32_t samples)
    : ctx_(ctx), scene_(scene), width_(width), height_(height) {
  // Device memory by use: what each step below adds to the context's count.
  uint64_t mark = ctx.memory_in_use;
  auto take = [&] {
    uint64_t now = ctx.memory_in_use, added = now - mark;
    mark = now;
    return added;
  };
  targets_ = create_render_targets(ctx, {width, height}, samples);
  memory_.targets = take();
  buffers_ = upload_scene(ctx, scene);
  memory_.textures = buffers_.leaf_textures.allocated + buffers_.bark_albedo.allocated + buffers_.bark_normals.allocated;
  memory_.impostors = buffers_.impostor_albedo.allocated + buffers_.impostor_normals.allocated;
  memory_.geometry = take() - memory_.textures - memory_.impostors;
  descriptors_ = create_descriptor_table(ctx, kRendererBindingLists, kFramesInFlight);
  const VkPushConstantRange push_ranges[] = {kPrCountPushRange, kDrawPushRange};
  layout_ = vk::create_pipeline_layout(ctx, descriptors_.layout, push_ranges);

  cull_ = create_cull_pass(ctx, layout_, buffers_.instance_count);
  tail_cull_ = create_tail_cull_pass(ctx, layout_, buffers_.instance_count, buffers_.instance_leaves);
  draw_ = create_draw_pass(ctx, layout_, targets_.samples, scene.desc.leaf_shadows_per_fragment);
  pr_count_ = create_pr_count_pass(ctx, layout_, targets_.extent);
  pyramid_overlay_ = create_pyramid_overlay_pass(ctx, layout_);
  memory_.passes = take();
  const uint32_t shadow_resolution =
      scene.desc.shadow_resolution > 0 ? scene.desc.shadow_resolution : shadow_resolution_for(height);
  shadow_ = create_shadow_pass(ctx, layout_, buffers_.instance_count, shadow_resolution);
  memory_.shadows = take();
  impostors_ = create_impostor_pass(ctx, layout_, buffers_.instance_count, targets_.samples);
  memory_.impostors += take();
  shadow_bounds_ = scene_shadow_bounds(scene);
  pyramid_ = create_depth_pyramid(ctx, targets_.pyramid_source().view, targets_.extent, true);
  image_readback_ = vk::create_buffer(ctx, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                      vk::MemoryUse::readback);
  memory_.targets += take();
  create_slots();
  write_descriptors();
  memory_.passes += take();
}

void Renderer::create_slots() {
  for (uint32_t i = 0; i < kFramesInFlight; ++i) {
    FrameSlot& s = slots_[i];
    s.set = descriptors_.sets[i];
    s.frame = vk::create_buffer(ctx_, sizeof(gpu::FrameData),
                                VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::upload);
    s.counts_readback = vk::create_buffer(ctx_, sizeof(gpu::DrawCounts), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                          vk::MemoryUse::readback);
    VkQueryPoolCreateInfo qpci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qpci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qpci.queryCount = kTimestampCount;
    VK_CHECK(vkCreateQueryPool(ctx_.device, &qpci, nullptr, &s.timestamps));
    s.pipeline_stats = create_gpu_stats(ctx_);
    s.cmd = vk::allocate_command_buffer(ctx_);
    s.fence = vk::create_fence(ctx_, false);
  }
}

// Every binding by its number; the sets of the frames in flight differ only in their frame
// constants. Also after the coverage buffers grew (no submit is pending then).
void Renderer::write_descriptors() {
  for (const FrameSlot& s : slots_) {
    DescriptorWrites w;
    w.buffer(BINDING_FRAME, s.frame);
    write_scene_bindings(w, buffers_);
    write_cull_bindings(w, cull_);
    write_tail_cull_bindings(w, tail_cull_);
    write_pr_count_bindings(w, pr_count_);
    write_shadow_bindings(w, shadow_);
    write_impostor_bindings(w, impostors_);
    w.image(BINDING_DEPTH_PYRAMID, pyramid_.point_sampler, pyramid_.image.view, VK_IMAGE_LAYOUT_GENERAL);
    w.apply(ctx_, descriptors_, s.set, true);
  }
}

Renderer::~Renderer() {
  VkDevice dev = ctx_.device;
  vkDeviceWaitIdle(dev);
  for (FrameSlot& s : slots_) {
    vkDestroyFence(dev, s.fence, nullptr);
    vkFreeCommandBuffers(dev, ctx_.command_pool, 1, &s.cmd);
    vkDestroyQueryPool(dev, s.timestamps, nullptr);
    destroy_gpu_stats(ctx_, s.pipeline_stats);
    vk::destroy_buffer(ctx_, s.frame);
    vk::destroy_buffer(ctx_, s.counts_readback);
  }
  vk::destroy_buffer(ctx_, image_readback_);
  destroy_depth_pyramid(ctx_, pyramid_);
  destroy_pyramid_overlay_pass(ctx_, pyramid_overlay_);
  destroy_shadow_pass(ctx_, shadow_);
  destroy_impostor_pass(ctx_, impostors_);
  destroy_pr_count_pass(ctx_, pr_count_);
  destroy_draw_pass(ctx_, draw_);
  destroy_tail_cull_pass(ctx_, tail_cull_);
  destroy_cull_pass(ctx_, cull_);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  destroy_descriptor_table(ctx_, descriptors_);
  destroy_scene_buffers(ctx_, buffers_);
  destroy_render_targets(ctx_, targets_);
}

void Renderer::record_pyramid(VkCommandBuffer cmd) {
  // The finished depth (or its resolve) becomes the pyramid's source.
  vk::image_barrier(cmd, targets_.pyramid_source().image, VK_IMAGE_ASPECT_DEPTH_BIT,
                    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                    VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  record_depth_pyramid(cmd, pyramid_);
}

bool Renderer::camera_cut(const CameraMatrices& cm, const CameraDesc& camera, const FrameSettings& settings) const {
  if (settings.camera_cut || !pyramid_valid_) return true;
  if (camera.fov_deg != pyramid_camera_.fov_deg || camera.near != pyramid_camera_.near ||
      camera.ortho_height != pyramid_camera_.ortho_height)
    return true;
  if (glm::distance(cm.position, pyramid_camera_.position) > kCutDistance) return true;
  glm::vec3 before = glm::normalize(pyramid_camera_.target - pyramid_camera_.position);
  return glm::dot(before, cm.forward) < std::cos(glm::radians(kCutAngleDeg));
}

namespace {

// `count` elements of T from `src` at byte `offset`, after the device is idle.
template <class T>
std::vector<T> read_back(vk::Context& ctx, const vk::Buffer& src, size_t count, VkDeviceSize offset = 0) {
  std::vector<T> out(count);
  if (out.empty()) return out;
  VkDeviceSize bytes = sizeof(T) * out.size();
  vk::Buffer readback = vk::create_buffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::readback);
  vk::submit_now(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy copy{offset, 0, bytes};
    vkCmdCopyBuffer(cmd, src.buffer, readback.buffer, 1, &copy);
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  std::memcpy(out.data(), readback.mapped, bytes);
  vk::destroy_buffer(ctx, readback);
  return out;
}

}  // namespace

std::vector<gpu::InstanceState> Renderer::instance_states() {
  drain();
  return read_back<gpu::InstanceState>(ctx_, cull_.instance_states, buffers_.instance_count);
}

std::vector<Renderer::TailList> Renderer::tail_lists(bool instanced_leaves) {
  drain();
  gpu::DrawCounts counts = read_back<gpu::DrawCounts>(ctx_, cull_.counts, 1)[0];
  std::vector<gpu::TailJob> jobs = read_back<gpu::TailJob>(ctx_, tail_cull_.jobs, counts.tail_jobs);
  std::vector<uint32_t> leaves = read_back<uint32_t>(ctx_, tail_cull_.leaves, tail_cull_.capacity);
  std::vector<TailList> out;
  for (const gpu::TailJob& job : jobs) {
    gpu::DrawCommand d = read_back<gpu::DrawCommand>(ctx_, cull_.commands, 1, sizeof(gpu::DrawCommand) * job.command)[0];
    uint32_t kept = instanced_leaves ? d.instance_count : d.index_count / LEAF_POINT_INDICES;  // set_leaf_count
    TailList t{job, d.leaf_list, kept, {}};
    if (job.base + uint64_t(kept) <= leaves.size()) t.leaves.assign(leaves.begin() + job.base, leaves.begin() + job.base + kept);
    out.push_back(std::move(t));
  }
  return out;
}

void Renderer::record_scene(VkCommandBuffer cmd, const FrameSlot& slot, const DrawList& list, bool occlusion, bool timed) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &slot.set, 0, nullptr);
  if (timed) begin_gpu_stats(cmd, slot.pipeline_stats, StatsPass::cull);
  if (list.receiver_mask) record_receiver_mask(cmd, shadow_, pyramid_.size);
  record_cull_pass(cmd, cull_);
  if (list.shadows) {  // other counters and commands than cull.comp's, but the same buffers
    vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    record_shadow_cull(cmd, shadow_);
  }
  if (occlusion) record_tail_cull_pass(cmd, tail_cull_, cull_);
  if (timed) end_gpu_stats(cmd, slot.pipeline_stats, StatsPass::cull);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                         VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                         VK_ACCESS_2_TRANSFER_READ_BIT);
  if (timed) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, slot.timestamps, kCullEnd);
  if (timed) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.timestamps, kShadowStart);
  if (list.shadows)
    record_shadow_pass(cmd, shadow_, layout_, slot.set, buffers_, cull_, impostors_, list.instanced_leaves, list.shadow_terrain);
  if (timed) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.timestamps, kShadowEnd);
  if (timed) begin_gpu_stats(cmd, slot.pipeline_stats, StatsPass::draw);
  record_draw_pass(cmd, draw_, layout_, slot.set, buffers_, cull_, impostors_, targets_, list);
  if (timed) end_gpu_stats(cmd, slot.pipeline_stats, StatsPass::draw);
  color_layout_ = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
}

void Renderer::record_frame(FrameSlot& slot, Output output, const DrawList& list, bool occlusion, bool overlay) {
  VkCommandBuffer cmd = slot.cmd;
  vk::begin_commands(cmd);
  vkCmdResetQueryPool(cmd, slot.timestamps, 0, kTimestampCount);
  reset_gpu_stats(cmd, slot.pipeline_stats);
  // The frame before may still run on the queue (frames in flight): its reads and writes of
  // the shared GPU buffers come first.
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, slot.timestamps, kFrameStart);
  record_scene(cmd, slot, list, occlusion, true);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, slot.timestamps, kDrawEnd);
  if (overlay) record_pyramid_overlay_pass(cmd, pyramid_overlay_, layout_, slot.set, targets_);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.timestamps, kPyramidStart);
  if (occlusion) record_pyramid(cmd);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, slot.timestamps, kPyramidEnd);
  // Statistics always, pixels when asked.
  VkBufferCopy counts_copy{0, 0, sizeof(gpu::DrawCounts)};
  vkCmdCopyBuffer(cmd, cull_.counts.buffer, slot.counts_readback.buffer, 1, &counts_copy);
  record_output(cmd, output, slot.set);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.timestamps, kFrameEnd);
  VK_CHECK(vkEndCommandBuffer(cmd));
}

void Renderer::record_output(VkCommandBuffer cmd, Output output, VkDescriptorSet set) {
  if (output == Output::none) return;
  vk::image_barrier(cmd, targets_.color.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  VkBuffer target = output == Output::image       ? image_readback_.buffer
                    : output == Output::reference ? pr_count_.reference.buffer
                                                  : pr_count_.test.buffer;
  vkCmdCopyImageToBuffer(cmd, targets_.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target, 1, &region);
  color_layout_ = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  if (output != Output::compare) return;
  vkCmdFillBuffer(cmd, pr_count_.counts.buffer, 0, sizeof(gpu::PrCounts), 0);
  vk::memory_barrier(cmd, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // The depth pyramid may have bound its own sets since the cull pass.
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set, 0, nullptr);
  record_pr_count_pass(cmd, pr_count_, layout_, {width_ * height_, 0, PR_NO_MASK, 0, width_, 0u, PR_NO_MASK});
  record_pr_readback(cmd, pr_count_, 1);
}

FrameSettings scene_frame_settings(const SceneDesc& desc) {
  FrameSettings s;
  s.prune_mode = desc.prune_mode;
  s.quality = desc.quality;
  s.lambda_view = desc.lambda_view;
  s.mask = desc.mask_view;
  s.occlusion = desc.occlusion;
  s.shadows = desc.shadows;
  s.impostors = desc.impostors ? ImpostorMode::switched : ImpostorMode::off;
  return s;
}

double PrResult::quality() const {
  double p = precision(), r = recall();
  return 1.0 - std::sqrt((1.0 - p) * (1.0 - p) + (1.0 - r) * (1.0 - r));
}

FrameStats Renderer::render(const CameraDesc& camera, FrameImage* image) {
  return render(camera, image, scene_frame_settings(scene_.desc));
}

Renderer::FrameSlot& Renderer::render_and_wait(const CameraDesc& camera, const FrameSettings& settings, Output output) {
  drain();
  FrameSlot& slot = next_slot();
  prepare_frame(slot, camera, settings, output);
  submit(slot);
  wait(slot);
  return slot;
}

FrameStats Renderer::render(const CameraDesc& camera, FrameImage* image, const FrameSettings& settings) {
  FrameStats stats = read_stats(render_and_wait(camera, settings, image ? Output::image : Output::none));
  if (image) {
    image->width = width_;
    image->height = height_;
    image->rgba.resize(size_t(width_) * height_ * 4);
    std::memcpy(image->rgba.data(), image_readback_.mapped, image->rgba.size());
  }
  return stats;
}

std::optional<FrameStats> Renderer::render_async(const CameraDesc& camera, const FrameSettings& settings) {
  FrameSlot& slot = next_slot();
  std::optional<FrameStats> earlier;
  if (slot.pending) {
    wait(slot);
    earlier = read_stats(slot);
  }
  prepare_frame(slot, camera, settings, Output::none);
  submit(slot);
  return earlier;
}

void Renderer::render_reference(const CameraDesc& camera, const FrameSettings& reference) {
  FrameSettings s = reference;
  s.mask = true;
  render_and_wait(camera, s, Output::reference).pending = false;
}

PrResult Renderer::compare_with_reference(const CameraDesc& camera, const FrameSettings& test) {
  FrameSettings s = test;
  s.mask = true;
  render_and_wait(camera, s, Output::compare).pending = false;
  gpu::PrCounts c = read_pr_counts(pr_count_, 1)[0];
  return {c.tp, c.fp, c.fn};
}

gpu::FrameData Renderer::frame_data(const CameraDesc& camera, const FrameSettings& settings) const {
  return frame_data(camera, camera_matrices(camera, float(width_) / float(height_)), settings);
}

gpu::FrameData Renderer::frame_data(const CameraDesc& camera, const CameraMatrices& cm,
                                    const FrameSettings& settings) const {
  const SkyDesc& sky = scene_.desc.sky;
  gpu::FrameData fd{};
  fd.view_proj = cm.view_proj;
  fd.inv_view_proj = glm::inverse(cm.view_proj);
  fd.camera_pos = glm::vec4(cm.position, settings.solo_instance ? float(*settings.solo_instance + 1) : 0.0f);
  fd.sun_dir = glm::vec4(sky.sun_direction, sky.sun_intensity);
  fd.sky_zenith = glm::vec4(sky.zenith, 1.0f);
  fd.sky_horizon = glm::vec4(sky.horizon, 1.0f);
  fd.fog = glm::vec4(sky.horizon, sky.fog_density);
  for (size_t i = 0; i < 6; ++i) fd.frustum[i] = cm.frustum[i];
  // The cull pass divides by the distance: an orthographic camera's constant scale is
  // given as the perspective one that matches it at the target.
  float pixels_per_meter = camera.ortho_height > 0.0f
                               ? float(height_) / camera.ortho_height * glm::distance(camera.position, camera.target)
                               : focal_pixels(float(height_), camera.fov_deg);
  fd.lod = glm::vec4(pixels_per_meter, scene_.desc.lod_error_pixels, 0.0f, 0.0f);
  // The prune distance of the frame the scene states it for, scaled to this frame's pixels: a
  // tree prunes alike where it covers as many pixels (SceneDesc::prune_focal_pixels).
  const float focal = scene_.desc.prune_focal_pixels;
  const float prune_distance = scene_.desc.prune_distance * (focal > 0.0f ? pixels_per_meter / focal : 1.0f);
  fd.prune = glm::vec4(prune_distance, scene_.desc.transition,
                       settings.prune_mode == PruneMode::target ? settings.quality : settings.fixed_lambda,
                       settings.fixed_scale);
  fd.lod_camera = glm::vec4(settings.lod_camera ? *settings.lod_camera : cm.position, 1.0f);
  fd.prune_mode = uint32_t(settings.prune_mode);
  // Pulled leaves need quad cards and a geometry shader (leaf_card.geom); else instances. The
  // wireframe view draws instances too: lavapipe drew the geometry shader's triangles in line
  // mode as lines from each corner to one point of the screen (gpu.GpuWireframe.*).
  const bool instanced =
      settings.instanced_leaves || settings.wireframe || !buffers_.leaves_pullable || !ctx_.geometry_shader;
  fd.view_flags = (settings.lambda_view ? VIEW_LAMBDA : 0u) | (settings.mask ? VIEW_MASK : 0u) |
                  (settings.shadow_view ? VIEW_SHADOW : 0u) | (instanced ? VIEW_LEAF_INSTANCED : 0u) |
                  (settings.impostor_bake == ImpostorBake::albedo ? VIEW_IMPOSTOR_ALBEDO : 0u) |
                  (settings.impostor_bake == ImpostorBake::normal ? VIEW_IMPOSTOR_NORMAL : 0u);
  fd.impostors = uint32_t(settings.impostors);
  fd.impostor = glm::vec4(settings.impostor_heights, settings.impostor_cutoff, 0.0f);
  fd.camera_forward = glm::vec4(cm.forward, 0.0f);
  fd.light = glm::vec4(scene_.desc.exposure, 0.0f, 0.0f, 0.0f);
  if (settings.shadows && !settings.mask && settings.impostor_bake == ImpostorBake::none) {
    ShadowCascades sc = compute_shadow_cascades(camera, float(width_) / float(height_), sky.sun_direction,
                                                scene_.desc.shadow_distance, shadow_.resolution, shadow_bounds_);
    fd.shadows = 1;
    for (uint32_t c = 0; c < SHADOW_CASCADES; ++c) {
      fd.shadow_view_proj[c] = sc.cascades[c].view_proj;
      for (uint32_t p = 0; p < 6; ++p) fd.shadow_planes[c * 6 + p] = sc.cascades[c].planes[p];
      fd.shadow_splits[int(c)] = sc.cascades[c].split_far;
      fd.shadow_texel[int(c)] = sc.cascades[c].texel;
    }
    fd.shadow_splits.w = sc.distance;
    fd.shadow_texel.w = float(shadow_.resolution);
  }
  fd.instance_count = buffers_.instance_count;
  fd.leaf_command_base = buffers_.instance_count;
  fd.tail_capacity = tail_cull_.capacity;
  // tail_cull.comp runs one workgroup per job, dispatched indirectly: never more than the
  // device's group count (65535 guaranteed; a scene may hold 1 M trees).
  fd.tail_job_capacity = std::min(buffers_.instance_count, ctx_.properties.limits.maxComputeWorkGroupCount[0]);
  return fd;
}

Renderer::FrameSlot& Renderer::next_slot() { return slots_[frame_count_ % kFramesInFlight]; }

void Renderer::drain() {
  for (FrameSlot& s : slots_)
    if (s.pending) {
      wait(s);
      s.pending = false;
    }
}

void Renderer::submit(FrameSlot& slot) {
  auto cpu_start = std::chrono::steady_clock::now();
  VK_CHECK(vkResetFences(ctx_.device, 1, &slot.fence));
  vk::submit_commands(ctx_, slot.cmd, slot.fence);
  slot.stats.cpu_submit_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
  slot.pending = true;
  ++frame_count_;
}

void Renderer::wait(FrameSlot& slot) { VK_CHECK(vkWaitForFences(ctx_.device, 1, &slot.fence, VK_TRUE, UINT64_MAX)); }

void Renderer::prepare_frame(FrameSlot& slot, const CameraDesc& camera, const FrameSettings& settings, Output output) {
  auto cpu_start = std::chrono::steady_clock::now();
  CameraMatrices cm = camera_matrices(camera, float(width_) / float(height_));
  gpu::FrameData fd = frame_data(camera, cm, settings);
  const bool cut = settings.occlusion && camera_cut(cm, camera, settings);
  if (settings.occlusion) {
    fd.occlusion = OCCLUSION_ON | (cut ? OCCLUSION_CUT : 0u);
    fd.prev_view_proj = pyramid_view_proj_;
    fd.prev_inv_view_proj = glm::inverse(pyramid_view_proj_);
    fd.prev_camera = glm::vec4(pyramid_camera_.position, pyramid_camera_.near);
    fd.pyramid = glm::vec4(float(pyramid_.size.width), float(pyramid_.size.height), float(pyramid_.levels), 0.0f);
  }
  // The receiver mask needs a previous frame that saw nearly what this one sees.
  fd.receiver_mask =
      fd.shadows == 1 && settings.occlusion && !cut && pyramid_has_receivers_ && settings.receiver_mask ? 1u : 0u;
  std::memcpy(slot.frame.mapped, &fd, sizeof(fd));
  DrawList list;
  // Coverage and impostor bake frames: the trees alone on black.
  const bool trees_alone = settings.mask || settings.impostor_bake != ImpostorBake::none;
  list.background = !trees_alone;
  list.branches = settings.branches;
  list.wireframe = settings.wireframe && has_wireframe() && !trees_alone;
  list.keep_depth = settings.occlusion;
  list.shadows = settings.shadows && !trees_alone;
  list.receiver_mask = list.shadows && fd.receiver_mask == 1;
  list.impostors = settings.impostors != ImpostorMode::off;
  list.instanced_leaves = (fd.view_flags & VIEW_LEAF_INSTANCED) != 0;
  list.views = draws_a_view(fd.view_flags);
  // The terrain where a view sees it: the camera's side and near planes (its projection has no
  // far plane), a cascade's four sides (toward and away from the sun it holds every caster).
  uint32_t terrain_indices = 0;
  if (list.background) {
    list.terrain = visible_chunks(buffers_.terrain_chunks, std::span(cm.frustum).first(5));
    for (const IndexRange& r : list.terrain) terrain_indices += r.count;
  }
  if (list.shadows)
    for (uint32_t c = 0; c < SHADOW_CASCADES; ++c)
      list.shadow_terrain[c] = visible_chunks(buffers_.terrain_chunks, std::span(&fd.shadow_planes[c * 6], 4));
  // The overlay shows the pyramid this frame's cull pass read: one built by an earlier frame.
  const bool overlay = settings.pyramid_overlay && settings.occlusion && !settings.mask && pyramid_valid_;
  record_frame(slot, output, list, settings.occlusion, overlay);
  // The pyramid now holds this frame (or nothing usable, without occlusion).
  pyramid_valid_ = settings.occlusion;
  pyramid_has_receivers_ = list.background;
  pyramid_view_proj_ = cm.view_proj;
  pyramid_camera_ = camera;
  slot.stats = {};
  slot.stats.instances = buffers_.instance_count;
  slot.stats.terrain_triangles = terrain_indices / 3;
  slot.stats.camera_cut = cut;
  slot.stats.cpu_submit_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpu_start).count();
}

FrameStats Renderer::read_stats(FrameSlot& slot) {
  slot.pending = false;
  FrameStats stats = slot.stats;
  gpu::DrawCounts counts;
  std::memcpy(&counts, slot.counts_readback.mapped, sizeof(counts));
  stats.branch_draws = counts.branch_draws;
  stats.leaf_draws = counts.leaf_draws;
  stats.leaves_drawn = counts.leaves_drawn;
  stats.branch_triangles = counts.branch_triangles;
  for (int k = 0; k < MAX_BRANCH_LODS; ++k) stats.lod_draws[k] = counts.lod_draws[k];
  stats.mean_lambda = counts.branch_draws ? double(counts.lambda_sum) / 4096.0 / counts.branch_draws : 0.0;
  stats.occluded_instances = counts.occluded_instances;
  stats.leaves_saved = counts.leaves_saved;
  stats.triangles_saved = counts.triangles_saved;
  std::array<uint64_t, kTimestampCount> ts{};
  VK_CHECK(vkGetQueryPoolResults(ctx_.device, slot.timestamps, 0, kTimestampCount, sizeof(ts), ts.data(), sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  double period_ms = double(ctx_.properties.limits.timestampPeriod) * 1e-6;
  stats.cull_ms = double(ts[kCullEnd] - ts[kFrameStart]) * period_ms;
  stats.draw_ms = double(ts[kDrawEnd] - ts[kCullEnd]) * period_ms;
  stats.frame_ms = double(ts[kFrameEnd] - ts[kFrameStart]) * period_ms;
  stats.pyramid_ms = double(ts[kPyramidEnd] - ts[kPyramidStart]) * period_ms;
  stats.shadow_ms = double(ts[kShadowEnd] - ts[kShadowStart]) * period_ms;
  stats.draw_ms = std::max(stats.draw_ms - stats.shadow_ms, 0.0);  // the camera's draw pass alone
  for (int c = 0; c < SHADOW_CASCADES; ++c) {
    stats.shadow_casters[c] = counts.shadow_branch_draws[c];
    stats.shadow_triangles[c] = counts.shadow_triangles[c];
    stats.shadow_leaves[c] = counts.shadow_leaves[c];
    stats.shadow_impostors[c] = counts.impostor_draws[1 + c].instance_count;
  }
  stats.impostors = counts.impostor_draws[0].instance_count;
  stats.cull_pipeline = read_gpu_stats(ctx_, slot.pipeline_stats, StatsPass::cull);
  stats.draw_pipeline = read_gpu_stats(ctx_, slot.pipeline_stats, StatsPass::draw);
  return stats;
}

}  // namespace forest
