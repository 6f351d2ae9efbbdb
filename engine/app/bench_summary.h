// The per-mode summaries of `forest bench` (cmd_bench.cpp) and what is derived from them:
// per-frame CSV, the plots along the path, the per-tree PR figures (--tree-pr) and Neubert
// 2012 Table 7.4 / Fig 7.17 per frame against Cook's.
#pragma once
#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bench/bench_run.h"

namespace forest::app {

struct ModeSummary {
  BenchMode mode;
  std::vector<BenchFrame> frames;
  double gpu_frame_ms = 0, gpu_draw_ms = 0, gpu_cull_ms = 0, gpu_pyramid_ms = 0, cpu_ms = 0;
  double triangles = 0, vertices = 0, leaves = 0, visible = 0, lambda = 0, quality = 0, precision = 0, recall = 0;
  double leaves_saved = 0, triangles_saved = 0, occluded = 0;  // by occlusion feedback, per frame
  double gpu_shadow_ms = 0, shadow_casters[SHADOW_CASCADES] = {}, shadow_triangles[SHADOW_CASCADES] = {};
  double impostors = 0, shadow_impostors[SHADOW_CASCADES] = {};  // per frame
  uint32_t pr_frames = 0;
  MemoryReport memory;  // device memory of the renderer that played the mode
  // Shares of what the mode would draw without occlusion, and of the GPU frame.
  double leaves_saved_share() const { return leaves_saved / std::max(leaves + leaves_saved, 1.0); }
  double triangles_saved_share() const { return triangles_saved / std::max(triangles + triangles_saved, 1.0); }
  double occlusion_gpu_share() const { return gpu_frame_ms > 0 ? (gpu_pyramid_ms + gpu_cull_ms) / gpu_frame_ms : 0.0; }
};

ModeSummary summarize(const BenchMode& mode, std::vector<BenchFrame> frames);
std::string frames_csv(const ModeSummary& m);
std::string trees_csv(const ModeSummary& m);  // --tree-pr: frame, time_s, size_px, q per tree; "" without
glm::vec3 mode_color(std::string name);  // plots: a colour of its own per bench mode, "+shadows" darker
// `value` of every frame of every mode against the time along the path, one PNG.
void write_path_plot(const std::vector<ModeSummary>& modes, const std::string& title, const std::string& y_label,
                     double (*value)(const BenchFrame&), const std::filesystem::path& file);
std::string tolerance_text();  // kEqualQualityTolerance as text

// Per-tree PR of a mode (--tree-pr): per PR frame the mean and 10th percentile of the trees'
// Q, and the worst of each over the frames.
struct TreePr {
  uint32_t frames = 0, min_trees = ~0u;
  double worst_mean = 1, worst_p10 = 1, mean = 0;
  double p10 = 1;  // over all measured trees of all PR frames (the frames' own are 20-odd trees each)
};
TreePr tree_pr(const ModeSummary& m);
std::string tree_pr_note(const ModeSummary& m, float target);  // a paragraph of summary.md ("" without)

// Neubert 2012 Table 7.4 and Fig 7.17 from the played modes: per frame, the leaves each
// pruned mode draws against Cook's (its λ comes from tables that match Cook's Q at every
// distance and size, so this is geometry saved at equal Q, checked at the PR frames). A
// markdown section for summary.md ("" without a Cook mode), and the plot along the path.
std::string table_7_4_note(const std::vector<ModeSummary>& modes,
                           const std::function<const ModeSummary*(const ModeSummary&)>& cook_of,
                           const std::filesystem::path& plot_file, const std::string& label);

}  // namespace forest::app
