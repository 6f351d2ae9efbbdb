// Headless forest renderer: uploads a Scene once, then renders frames entirely from GPU
// buffers. A frame is a list of passes, each a small unit owning its pipeline and bindings:
// cull (cull_pass.h) → tail cull with occlusion (tail_cull_pass.h) → draw (draw_pass.h) →
// depth pyramid with occlusion (engine/occlusion/depth_pyramid.h) → readback; coverage
// comparisons add the count pass (pr_count_pass.h). The descriptor set layout is the union
// of what the passes declare (descriptor_table.h). Per-frame CPU work is O(1) in the number
// of tree instances. Two frames in flight (render_async, for `forest walk`).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/occlusion/depth_pyramid.h"
#include "engine/render/cull_pass.h"
#include "engine/render/descriptor_table.h"
#include "engine/render/draw_pass.h"
#include "engine/render/gpu_stats.h"
#include "engine/render/impostor_pass.h"
#include "engine/render/pr_count_pass.h"
#include "engine/render/pyramid_overlay_pass.h"
#include "engine/render/render_targets.h"
#include "engine/render/scene_buffers.h"
#include "engine/render/shadow_cascades.h"
#include "engine/render/shadow_pass.h"
#include "engine/render/tail_cull_pass.h"
#include "engine/scene/camera.h"
#include "engine/scene/scene.h"
#include "engine/vk/resources.h"

namespace forest {

struct FrameImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;  // sRGB, row-major, top row first
  const uint8_t* pixel(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

// Far trees as impostors (FrameData.impostors, impostor_pass.h).
enum class ImpostorMode : uint32_t {
  off = IMPOSTORS_OFF,
  switched = IMPOSTORS_SWITCHED,  // where the baked Q says the impostor is at least as good ([render] impostors)
  always = IMPOSTORS_ALWAYS,      // every tree that has one (the bake's quality measurement, tests)
};
// The impostor bake's renders (impostor_bake.h): coverage is a mask frame, then these.
enum class ImpostorBake { none, albedo, normal };

// Per-frame choices that override the scene's [render] settings.
struct FrameSettings {
  PruneMode prune_mode = PruneMode::full;
  float fixed_lambda = 1.0f;  // PruneMode::fixed
  float fixed_scale = 1.0f;   // PruneMode::fixed: leaf area scale s
  float quality = 0.95f;      // PruneMode::target: the Q each tree keeps at its projected size
  bool mask = false;          // coverage only: trees white on black, no sky or terrain
  bool branches = true;       // false: leaves alone, no bark (leaf coverage measurements)
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
  // Debug overlay: the depth pyramid the occlusion test reads, in the top-right quarter
  // (pyramid_overlay_pass.h). Drawn only with occlusion on; never in coverage (mask) frames.
  bool pyramid_overlay = false;
  // The sun's cascaded shadow maps ([render] shadows, --shadows). Coverage (mask) frames never
  // draw them: PR measurements do not depend on light.
  bool shadows = false;
  // Shows the shadow map's sun visibility as grey on terrain and trees (tests, debugging).
  bool shadow_view = false;
  // With shadows and occlusion: casters whose shadow falls on no surface the previous frame
  // saw are skipped per cascade (receiver_mask.comp). Off: every caster in a cascade's volume
  // is drawn (tests compare the two).
  bool receiver_mask = true;
  // Leaves as instances of their card instead of by vertex pulling (leaf_draw.glsl): the
  // comparison of `forest bench`'s mode opt-occl-instanced. Pulled unless set (or unless a
  // model's card is not a quad).
  bool instanced_leaves = false;
  // Draw this instance alone (its index in Scene::instances), every other tree culled: the
  // per-tree PR of `forest bench --tree-pr` (each tree against its own full-detail mask).
  std::optional<uint32_t> solo_instance;
  ImpostorMode impostors = ImpostorMode::off;
  // Impostor bake frames (no background, no shadows, like mask frames); with `normal`,
  // impostor_heights = (view depth of the model's centre, 1 / (2 · its radius)).
  ImpostorBake impostor_bake = ImpostorBake::none;
  glm::vec2 impostor_heights{0.0f};
  float impostor_cutoff = 0.0f;  // > 0: every impostor's coverage cutoff (the bake's search)
};
FrameSettings scene_frame_settings(const SceneDesc& desc);

struct FrameStats {
  uint32_t instances = 0;
  uint32_t branch_draws = 0;   // visible trees
  uint32_t leaf_draws = 0;
  uint32_t leaves_drawn = 0;
  uint32_t branch_triangles = 0;
  uint32_t terrain_triangles = 0;  // drawn by the draw pass (the chunks the camera sees, terrain_cull.h)
  uint32_t lod_draws[MAX_BRANCH_LODS] = {};  // visible trees per branch LOD level
  double mean_lambda = 0.0;                   // over visible trees
  uint32_t occluded_instances = 0;  // in the frustum, culled by occlusion
  uint32_t leaves_saved = 0;        // by occlusion: leaves the mode alone would have drawn, minus drawn
  uint32_t triangles_saved = 0;     // by occlusion: leaf + branch triangles
  bool camera_cut = false;          // occlusion treated every tree as visible this frame
  double pyramid_ms = 0.0;          // GPU time of the depth pyramid (0 without occlusion)
  double shadow_ms = 0.0;           // GPU time of the shadow pass (cull + cascades; 0 without shadows)
  uint32_t shadow_casters[SHADOW_CASCADES] = {};    // trees drawn into each cascade
  uint32_t shadow_triangles[SHADOW_CASCADES] = {};  // bark + leaf triangles drawn into each cascade
  uint32_t shadow_leaves[SHADOW_CASCADES] = {};
  uint32_t impostors = 0;                           // trees drawn as impostors (in the cross-fade band also as meshes)
  uint32_t shadow_impostors[SHADOW_CASCADES] = {};  // impostor casters per cascade
  double cull_ms = 0.0;        // GPU timestamps
  double draw_ms = 0.0;        // the draw pass (sky, terrain, trees), without the shadow pass
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

// Counts of one coverage render at each PR size: [0] at the render's resolution, [b] at 2^-b
// of it (the lattices of gpu_types.h).
using PrSizes = std::array<PrResult, PR_SIZES>;
// Counts of one coverage render per sub-pixel phase of each size b >= 1 (PR_PHASE_BINS).
using PrPhases = std::vector<PrResult>;

// One pruned coverage render of a batch: the model at detail λ with leaf area scale s, seen
// from one of the views given to Renderer::set_coverage_views.
struct CoverageJob {
  uint32_t view = 0;
  float lambda = 1.0f, scale = 1.0f;
};

// Set 0 of every renderer pipeline: the union of the bindings its passes declare.
inline constexpr std::span<const Binding> kRendererBindingLists[] = {kSceneBindings, kCullBindings, kTailCullBindings,
                                                                     kDrawBindings, kPrCountBindings,
                                                                     kPyramidOverlayBindings, kShadowBindings,
                                                                     kImpostorBindings};

// Device memory a renderer holds, by use (bytes of vkAllocateMemory: Context::memory_in_use
// over its construction, host-visible readback buffers included).
struct MemoryReport {
  uint64_t geometry = 0;   // vertices, indices, instances, models, leaves, PR tables, hull samples
  uint64_t textures = 0;   // leaf and bark textures
  uint64_t impostors = 0;  // impostor atlases (impostor_textures.h) and the impostor lists
  uint64_t shadows = 0;    // the cascades' shadow map and receiver mask
  uint64_t targets = 0;    // colour, depth, resolve, depth pyramid, readback
  uint64_t passes = 0;     // per-frame work: indirect commands, counts, occlusion state, frame slots
  uint64_t total() const { return geometry + textures + impostors + shadows + targets + passes; }
};

class Renderer {
 public:
  static constexpr uint32_t kFramesInFlight = 2;

  // `samples`: MSAA samples per pixel, lowered to what the device supports.
  Renderer(vk::Context& ctx, const Scene& scene, uint32_t width, uint32_t height, uint32_t samples = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame and waits for it; fills `image` when given.
  FrameStats render(const CameraDesc& camera, FrameImage* image);
  FrameStats render(const CameraDesc& camera, FrameImage* image, const FrameSettings& settings);
  // Records and submits one frame without waiting for it, so the CPU prepares the next frame
  // while the GPU draws this one (`forest walk`). Returns the statistics of the frame two calls
  // back, the last one this call's slot ran: its queries are read only when the slot is
  // reused, never waited for while the frame in between may still run; nullopt for the first
  // two calls. The frame's colour image may be read by later work on the same queue
  // (present) as after render().
  std::optional<FrameStats> render_async(const CameraDesc& camera, const FrameSettings& settings);

  // Coverage comparisons on the GPU: render the reference coverage once per view, then
  // compare any number of test settings against it; only three counts come back.
  void render_reference(const CameraDesc& camera, const FrameSettings& reference);
  PrResult compare_with_reference(const CameraDesc& camera, const FrameSettings& test);

  // Batched coverage comparisons (PR bake, single-sampled renderers only; coverage_batch.cpp).
  // Stores per view the full-detail coverage and the branch-only coverage on the GPU (one
  // submit); compare_coverage then draws only the leaf prefix of each job, ORs in its view's
  // branch mask and counts against its reference — at size 0 the same counts as
  // render_reference + compare_with_reference, without redrawing the branches — all jobs in
  // one submit. Every render also counts the coverage at the smaller PR sizes (lattices).
  void set_coverage_views(const std::vector<CameraDesc>& views);
  // With `phases`, also each job's counts per sub-pixel phase of the smaller sizes
  // (PR_PHASE_BINS, indexed by prune::phase_bin): one small render's counts each.
  std::vector<PrSizes> compare_coverage(const std::vector<CoverageJob>& jobs, std::vector<PrPhases>* phases = nullptr);

  // Occlusion feedback state of every instance, read back from the GPU (tests, tools).
  std::vector<gpu::InstanceState> instance_states();
  // The last frame's tail lists (tail_cull.comp), read back from the GPU (tests): per job, the
  // leaf range it tested, its draw's list kind and leaf count, and the leaves the tail leaf
  // buffer holds for it (empty if they would run past the buffer). `instanced_leaves`: the
  // frame drew leaves as instances (FrameSettings::instanced_leaves), which count otherwise.
  struct TailList {
    gpu::TailJob job;
    uint32_t leaf_list = 0;  // the job's draw: LEAF_LIST_TAIL
    uint32_t kept = 0;
    std::vector<uint32_t> leaves;
  };
  std::vector<TailList> tail_lists(bool instanced_leaves = false);
  const DepthPyramid& depth_pyramid() const { return pyramid_; }

  uint32_t samples() const { return uint32_t(targets_.samples); }
  const MemoryReport& memory() const { return memory_; }
  bool has_wireframe() const { return draw_.wire.terrain != VK_NULL_HANDLE; }
  // The resolved colour image of the last frame (sRGB, width × height) and the layout the
  // last render() left it in, for a present step that copies it to a window (forest walk).
  // The next render() discards its contents; reads must be ordered before it on the queue.
  const vk::Image& color_image() const { return targets_.color; }
  VkImageLayout color_layout() const { return color_layout_; }

 private:
  enum class Output { none, image, reference, compare };
  // What one frame in flight owns: its command buffer and fence, its frame constants (and
  // the descriptor set that binds them), its queries and its statistics readback.
  struct FrameSlot {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    bool pending = false;  // submitted, results not read yet
    VkDescriptorSet set = VK_NULL_HANDLE;
    vk::Buffer frame;            // FrameData (host-written, TRANSFER_DST for coverage batches)
    vk::Buffer counts_readback;  // DrawCounts
    VkQueryPool timestamps = VK_NULL_HANDLE;
    GpuStatsQueries pipeline_stats;
    FrameStats stats;  // what is known at submit (instances, camera cut, CPU time)
  };

  void create_slots();
  void write_descriptors();
  FrameSlot& next_slot();
  // Drains the frames in flight, then renders one frame and waits for it.
  FrameSlot& render_and_wait(const CameraDesc& camera, const FrameSettings& settings, Output output);
  void drain();  // waits for every frame in flight (results of render_async frames dropped)
  FrameStats read_stats(FrameSlot& slot);
  void submit(FrameSlot& slot);
  void wait(FrameSlot& slot);
  // Frame constants, occlusion state and recording of one frame into `slot`.
  void prepare_frame(FrameSlot& slot, const CameraDesc& camera, const FrameSettings& settings, Output output);
  // The one recording path of scene pictures, shared by frames and coverage batches: cull,
  // tail cull (with occlusion), draw. `timed`: timestamps and pipeline statistics of `slot`.
  void record_scene(VkCommandBuffer cmd, const FrameSlot& slot, const DrawList& list, bool occlusion, bool timed);
  void record_frame(FrameSlot& slot, Output output, const DrawList& list, bool occlusion, bool overlay);
  void record_output(VkCommandBuffer cmd, Output output, VkDescriptorSet set);
  void record_pyramid(VkCommandBuffer cmd);
  bool camera_cut(const CameraMatrices& cm, const CameraDesc& camera, const FrameSettings& settings) const;
  gpu::FrameData frame_data(const CameraDesc& camera, const FrameSettings& settings) const;
  gpu::FrameData frame_data(const CameraDesc& camera, const CameraMatrices& cm, const FrameSettings& settings) const;
  // Coverage batches (coverage_batch.cpp): one mask render recorded into `cmd`.
  void record_coverage_render(VkCommandBuffer cmd, const FrameSlot& slot, const gpu::FrameData& frame, bool branches,
                              bool leaves);
  void reserve_coverage(uint32_t reference_frames, uint32_t results);

  vk::Context& ctx_;
  const Scene& scene_;
  uint32_t width_, height_;
  RenderTargets targets_;
  SceneBuffers buffers_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  DescriptorTable descriptors_;
  CullPass cull_;
  TailCullPass tail_cull_;
  DrawPass draw_;
  PrCountPass pr_count_;
  PyramidOverlayPass pyramid_overlay_;
  ShadowPass shadow_;
  ImpostorPass impostors_;
  ShadowBounds shadow_bounds_;  // what may cast: terrain and trees
  DepthPyramid pyramid_;
  FrameSlot slots_[kFramesInFlight];
  uint32_t frame_count_ = 0;  // frames submitted; slots_[frame_count_ % kFramesInFlight] is next
  vk::Buffer image_readback_;
  std::vector<CameraDesc> coverage_views_;
  // The frame the pyramid holds: its camera, and whether it is usable at all.
  MemoryReport memory_;
  bool pyramid_valid_ = false;
  bool pyramid_has_receivers_ = false;  // built by a frame with its terrain (not a coverage frame)
  glm::mat4 pyramid_view_proj_{1.0f};
  CameraDesc pyramid_camera_;
  VkImageLayout color_layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
};

}  // namespace forest
