// Headless forest renderer: uploads a Scene once, then renders frames entirely from GPU
// buffers: cull.comp writes compacted indirect draws, drawn with DrawIndexedIndirectCount.
// Per-frame CPU work is O(1) in the number of tree instances.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/occlusion/depth_pyramid.h"
#include "engine/render/gpu_stats.h"
#include "engine/scene/camera.h"
#include "engine/scene/scene.h"
#include "engine/vk/resources.h"

namespace forest {

struct FrameImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // sRGB, row-major, top row first
  const uint8_t* pixel(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

// Per-frame choices that override the scene's [render] settings.
struct FrameSettings {
  uint32_t prune_mode = PRUNE_FULL;
  float fixed_lambda = 1.0f;  // PRUNE_FIXED
  float fixed_scale = 1.0f;   // PRUNE_FIXED: leaf area scale s
  bool mask = false;          // coverage only: trees white on black, no sky or terrain
  bool lambda_view = false;
  // Triangle edges instead of filled triangles (terrain, bark, leaf cards); ignored when the
  // device lacks fillModeNonSolid (Renderer::has_wireframe()).
  bool wireframe = false;
  // Depth-buffer occlusion feedback (Neubert 2012 §7.4): λ scaled by each tree's visibility in
  // the previous frame, hidden trees culled. The first frame, and any frame after a camera
  // cut (this flag, or a jump detected from the camera), counts every tree as visible.
  bool occlusion = false;
  bool camera_cut = false;
  // Choose branch LODs and λ as seen from this point instead of the camera: a frozen LOD
  // (`forest walk`, key K) to look at what the pruning keeps, and the popping measurement,
  // which changes the LOD viewpoint alone between two renders of one view.
  std::optional<glm::vec3> lod_camera;
};
FrameSettings scene_frame_settings(const SceneDesc& desc);

struct FrameStats {
  uint32_t instances = 0;
  uint32_t branch_draws = 0;   // visible trees
  uint32_t leaf_draws = 0;
  uint32_t leaves_drawn = 0;
  uint32_t branch_triangles = 0;
  uint32_t lod_draws[MAX_BRANCH_LODS] = {};  // visible trees per branch LOD level
  double mean_lambda = 0.0;                   // over visible trees
  uint32_t occluded_instances = 0;  // in the frustum, culled by occlusion
  uint32_t leaves_saved = 0;        // by occlusion: leaves the mode alone would have drawn, minus drawn
  uint32_t triangles_saved = 0;     // by occlusion: leaf + branch triangles
  bool camera_cut = false;          // occlusion treated every tree as visible this frame
  double pyramid_ms = 0.0;          // GPU time of the depth pyramid (0 without occlusion)
  double cull_ms = 0.0;        // GPU timestamps
  double draw_ms = 0.0;
  double frame_ms = 0.0;
  double cpu_submit_ms = 0.0;  // CPU: frame constants + record + submit, not the GPU wait
  PipelineStats cull_pipeline, draw_pipeline;  // pipeline-statistics queries per pass
};

// Precision/Recall of a test frame's coverage against a reference (Neubert 2012 §7.2.2).
struct PrResult {
  uint64_t tp = 0, fp = 0, fn = 0;
  // With nothing retrieved, precision is taken as 1 (no false pixel was drawn).
  double precision() const { return tp + fp ? double(tp) / double(tp + fp) : 1.0; }
  double recall() const { return tp + fn ? double(tp) / double(tp + fn) : 1.0; }
  // Q = 1 − √((1 − P)² + (1 − R)²)  (7.7)
  double quality() const;
  PrResult& operator+=(const PrResult& o) {
    tp += o.tp, fp += o.fp, fn += o.fn;
    return *this;
  }
};

// One pruned coverage render of a batch: the model at detail λ with leaf area scale s, seen
// from one of the views given to Renderer::set_coverage_views.
struct CoverageJob {
  uint32_t view = 0;
  float lambda = 1.0f, scale = 1.0f;
};

class Renderer {
 public:
  // `samples`: MSAA samples per pixel, lowered to what the device supports.
  Renderer(vk::Context& ctx, const Scene& scene, uint32_t width, uint32_t height, uint32_t samples = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame and waits for it; fills `image` when given.
  FrameStats render(const CameraDesc& camera, FrameImage* image);
  FrameStats render(const CameraDesc& camera, FrameImage* image, const FrameSettings& settings);

  // Coverage comparisons on the GPU: render the reference coverage once per view, then
  // compare any number of test settings against it; only three counts come back.
  void render_reference(const CameraDesc& camera, const FrameSettings& reference);
  PrResult compare_with_reference(const CameraDesc& camera, const FrameSettings& test);

  // Batched coverage comparisons (PR bake, single-sampled renderers only; coverage_batch.cpp).
  // Stores per view the full-detail coverage and the branch-only coverage on the GPU (one
  // submit); compare_coverage then draws only the leaf prefix of each job, ORs in its view's
  // branch mask and counts against its reference — the same counts as render_reference +
  // compare_with_reference, without redrawing the branches — all jobs in one submit.
  void set_coverage_views(const std::vector<CameraDesc>& views);
  std::vector<PrResult> compare_coverage(const std::vector<CoverageJob>& jobs);

  // Occlusion feedback state of every instance, read back from the GPU (tests, tools).
  std::vector<gpu::InstanceState> instance_states();
  const DepthPyramid& depth_pyramid() const { return pyramid_; }

 private:
  void create_pipelines();
  enum class Output { none, image, reference, compare };
  FrameStats submit(const CameraDesc& camera, const FrameSettings& settings, Output output);
  void record(VkCommandBuffer cmd, Output output, bool mask, bool build_pyramid);
  // Occlusion feedback (Neubert 2012 §7.4): per-model samples, per-instance state, the pyramid.
  void create_occlusion_resources(const std::vector<gpu::HullSample>& samples);
  void record_pyramid(VkCommandBuffer cmd);
  bool camera_cut(const CameraMatrices& cm, const CameraDesc& camera, const FrameSettings& settings) const;
  gpu::FrameData frame_data(const CameraDesc& camera, const FrameSettings& settings) const;
  // Returns the CPU milliseconds spent up to the queue submission (not the wait).
  double submit_and_wait();
  // Coverage batches: one mask render (branches and/or leaves) recorded into `cmd`.
  void record_coverage_pass(VkCommandBuffer cmd, const gpu::FrameData& frame, bool branches, bool leaves);
  void record_pr_count(VkCommandBuffer cmd, const gpu::PrCountPush& push);
  void reserve_coverage(uint32_t reference_frames, uint32_t results);
  std::vector<CameraDesc> coverage_views_;
  uint32_t reference_capacity_ = 1, result_capacity_ = 1;  // frames / PrCounts allocated

  vk::Context& ctx_;
  const Scene& scene_;
  uint32_t width_, height_;
  uint32_t instance_count_ = 0;
  uint32_t terrain_index_count_ = 0;

  vk::Buffer vertices_, indices_, instances_, models_, leaves_, prune_tables_;
  vk::Buffer frame_, commands_, counts_, counts_readback_, image_readback_;
  vk::Buffer coverage_reference_, coverage_test_, pr_counts_, pr_readback_;
  vk::Image leaf_textures_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  vk::Image color_, color_msaa_, depth_;  // color_msaa_ only when samples_ > 1
  vk::Image depth_resolve_;                // sample 0 of depth_ when samples_ > 1: the pyramid's source
  vk::Buffer hull_samples_, instance_states_;
  vk::Buffer tail_jobs_, tail_leaves_;  // per-leaf occlusion of partly hidden trees (tail_cull.comp)
  uint32_t tail_capacity_ = 1;
  DepthPyramid pyramid_;
  VkSampler pyramid_sampler_ = VK_NULL_HANDLE;
  // The frame the pyramid holds: its camera, and whether it is usable at all.
  bool pyramid_valid_ = false;
  glm::mat4 pyramid_view_proj_{1.0f};
  CameraDesc pyramid_camera_;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;

 public:
  uint32_t samples() const { return uint32_t(samples_); }
  bool has_wireframe() const { return terrain_wire_ != VK_NULL_HANDLE; }
  // The resolved colour image of the last frame (sRGB, width × height) and the layout the
  // last render() left it in, for a present step that copies it to a window (forest walk).
  // The next render() discards its contents; reads must be ordered before it on the queue.
  const vk::Image& color_image() const { return color_; }
  VkImageLayout color_layout() const { return color_layout_; }

 private:
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline cull_ = VK_NULL_HANDLE, tail_cull_ = VK_NULL_HANDLE, sky_ = VK_NULL_HANDLE, terrain_ = VK_NULL_HANDLE;
  VkPipeline branches_ = VK_NULL_HANDLE, leaves_pipeline_ = VK_NULL_HANDLE, pr_count_ = VK_NULL_HANDLE;
  VkPipeline terrain_wire_ = VK_NULL_HANDLE, branches_wire_ = VK_NULL_HANDLE, leaves_wire_ = VK_NULL_HANDLE;
  bool wireframe_ = false;  // this frame draws with the *_wire_ pipelines
  VkImageLayout color_layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
  VkQueryPool timestamps_ = VK_NULL_HANDLE;
  GpuStatsQueries pipeline_stats_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace forest
