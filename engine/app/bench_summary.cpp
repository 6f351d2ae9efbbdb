#include "engine/app/bench_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "engine/tools/report/plot.h"
#include "generators/asset/pr_tables.h"

namespace forest::app {

namespace {

// Per frame against Cook's (the same frames, in order; Cook with the same shadow setting).
struct PerFrameVsCook {
  std::vector<std::pair<float, float>> saved;  // (time, 1 − leaves / Cook's leaves), frames where Cook draws
  double mean = 0, min = 1, max = -1;
  double worst_q_delta = 1;  // min over the PR frames of Q − Q_Cook
  uint32_t pr_frames = 0;
};

PerFrameVsCook per_frame_vs_cook(const ModeSummary& m, const ModeSummary& cook) {
  PerFrameVsCook v;
  for (size_t i = 0; i < std::min(m.frames.size(), cook.frames.size()); ++i) {
    const BenchFrame &f = m.frames[i], &c = cook.frames[i];
    if (c.stats.leaves_drawn > 0) {
      double saved = 1.0 - double(f.stats.leaves_drawn) / double(c.stats.leaves_drawn);
      v.saved.push_back({float(f.time), float(saved)});
      v.mean += saved, v.min = std::min(v.min, saved), v.max = std::max(v.max, saved);
    }
    if (f.has_pr && c.has_pr) v.worst_q_delta = std::min(v.worst_q_delta, f.pr.quality() - c.pr.quality()), ++v.pr_frames;
  }
  if (!v.saved.empty()) v.mean /= double(v.saved.size());
  return v;
}

}  // namespace


ModeSummary summarize(const BenchMode& mode, std::vector<BenchFrame> frames) {
  ModeSummary s;
  s.mode = mode;
  double n = double(std::max<size_t>(frames.size(), 1));
  for (const BenchFrame& f : frames) {
    s.gpu_frame_ms += f.stats.frame_ms / n, s.gpu_draw_ms += f.stats.draw_ms / n, s.gpu_cull_ms += f.stats.cull_ms / n;
    s.gpu_pyramid_ms += f.stats.pyramid_ms / n, s.cpu_ms += f.stats.cpu_submit_ms / n;
    s.triangles += double(f.tree_triangles) / n, s.vertices += 3.0 * double(f.tree_triangles) / n;
    s.leaves += f.stats.leaves_drawn / n, s.visible += f.stats.branch_draws / n, s.lambda += f.stats.mean_lambda / n;
    s.leaves_saved += f.stats.leaves_saved / n, s.triangles_saved += f.stats.triangles_saved / n;
    s.occluded += f.stats.occluded_instances / n;
    s.gpu_shadow_ms += f.stats.shadow_ms / n;
    s.impostors += f.stats.impostors / n;
    for (int c = 0; c < SHADOW_CASCADES; ++c)
      s.shadow_casters[c] += f.stats.shadow_casters[c] / n, s.shadow_triangles[c] += f.stats.shadow_triangles[c] / n,
      s.shadow_impostors[c] += f.stats.shadow_impostors[c] / n;
    if (f.has_pr) {
      s.pr_frames++;
      s.quality += f.pr.quality(), s.precision += f.pr.precision(), s.recall += f.pr.recall();
    }
  }
  if (s.pr_frames) s.quality /= s.pr_frames, s.precision /= s.pr_frames, s.recall /= s.pr_frames;
  s.frames = std::move(frames);
  return s;
}

std::string frames_csv(const ModeSummary& m) {
  std::ostringstream o;
  o << "frame,time_s,gpu_cull_ms,gpu_draw_ms,gpu_pyramid_ms,gpu_frame_ms,cpu_ms,ia_primitives,tree_triangles,"
       "branch_triangles,leaves_drawn,instances_visible,occluded_instances,leaves_saved,triangles_saved,mean_lambda,"
       "gpu_shadow_ms,shadow_triangles,precision,recall,q,impostors\n";
  char buf[512];
  for (const BenchFrame& f : m.frames) {
    const FrameStats& s = f.stats;
    std::snprintf(buf, sizeof buf, "%u,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,%llu,%u,%u,%u,%u,%u,%u,%.5f,", f.frame,
                  f.time, s.cull_ms, s.draw_ms, s.pyramid_ms, s.frame_ms, s.cpu_submit_ms,
                  (unsigned long long)s.draw_pipeline.ia_primitives, (unsigned long long)f.tree_triangles,
                  s.branch_triangles, s.leaves_drawn, s.branch_draws, s.occluded_instances, s.leaves_saved,
                  s.triangles_saved, s.mean_lambda);
    o << buf;
    uint64_t shadow_triangles = 0;
    for (uint32_t t : s.shadow_triangles) shadow_triangles += t;
    std::snprintf(buf, sizeof buf, "%.4f,%llu,", s.shadow_ms, (unsigned long long)shadow_triangles);
    o << buf;
    if (f.has_pr) {
      std::snprintf(buf, sizeof buf, "%.5f,%.5f,%.5f", f.pr.precision(), f.pr.recall(), f.pr.quality());
      o << buf;
    } else {
      o << ",,";
    }
    o << "," << s.impostors << "\n";
  }
  return o.str();
}

glm::vec3 mode_color(std::string name) {
  const std::string suffix = "+shadows";
  if (name.size() > suffix.size() && name.ends_with(suffix)) {  // the same hue, darker
    name.resize(name.size() - suffix.size());
    return mode_color(name) * 0.6f;
  }
  if (name == "full") return {0.1f, 0.1f, 0.1f};
  if (name == "cook") return {0.85f, 0.25f, 0.15f};
  if (name == "opt") return {0.1f, 0.35f, 0.85f};
  if (name == "opt-combined") return {0.1f, 0.65f, 0.3f};
  if (name == "opt-random") return {0.3f, 0.6f, 0.95f};
  if (name == "opt-density") return {0.9f, 0.6f, 0.1f};
  if (name == "opt-orientation") return {0.55f, 0.35f, 0.15f};
  if (name == "opt-layered") return {0.0f, 0.55f, 0.55f};
  if (name == "cook-random") return {0.95f, 0.55f, 0.5f};
  if (name == "opt-occl") return {0.45f, 0.15f, 0.75f};
  if (name == "opt-occl-instanced") return {0.75f, 0.55f, 0.95f};
  if (name == "opt-occl-imp") return {0.9f, 0.1f, 0.6f};
  if (name == "target") return {0.55f, 0.55f, 0.0f};
  return {0.5f, 0.5f, 0.5f};  // a mode without a colour of its own
}

std::string tolerance_text() {
  char text[16];
  std::snprintf(text, sizeof text, "%g", kEqualQualityTolerance);
  return text;
}


std::string trees_csv(const ModeSummary& m) {
  std::ostringstream o;
  for (const BenchFrame& f : m.frames)
    for (size_t k = 0; k < f.tree_q.size(); ++k)
      o << f.frame << ',' << f.time << ',' << f.tree_size[k] << ',' << f.tree_q[k] << '\n';
  return o.str().empty() ? "" : "frame,time_s,size_px,q\n" + o.str();
}

// 10th percentiles by the rule of the bake's q_low (pr_tables.h low_quantile).
TreePr tree_pr(const ModeSummary& m) {
  TreePr t;
  std::vector<float> all;
  for (const BenchFrame& f : m.frames) {
    if (f.tree_q.empty()) continue;
    const std::vector<float>& q = f.tree_q;
    double mean = 0;
    for (float x : q) mean += x / double(q.size());
    double p10 = low_quantile(q, 0.1);
    all.insert(all.end(), q.begin(), q.end());
    t.worst_mean = std::min(t.worst_mean, mean), t.worst_p10 = std::min(t.worst_p10, p10);
    t.mean += mean, t.min_trees = std::min<uint32_t>(t.min_trees, uint32_t(q.size())), ++t.frames;
  }
  if (t.frames) t.mean /= t.frames;
  t.p10 = low_quantile(std::move(all), 0.1);
  return t;
}

std::string tree_pr_note(const ModeSummary& m, float target) {
  TreePr t = tree_pr(m);
  if (!t.frames) return "";
  char row[512];
  std::snprintf(row, sizeof row,
                "\nPer tree (%s; each tree drawn alone against its own full-detail mask, at least %u trees in each of "
                "%u PR frames): mean Q %.4f; worst frame's mean %.4f, worst frame's 10th percentile %.4f; 10th percentile of "
                "all trees %.4f%s\n",
                m.mode.name.c_str(), t.min_trees, t.frames, t.mean, t.worst_mean, t.worst_p10, t.p10,
                m.mode.prune_mode == PruneMode::target
                    ? (" (target " + std::to_string(target).substr(0, 5) + ": goals mean >= target, 10th percentile >= target - 0.03)").c_str()
                    : "");
  return row;
}

// Neubert 2012 Table 7.4 and Fig 7.17 from the played modes: per frame, the leaves each
// pruned mode draws against Cook's (its λ comes from tables that match Cook's Q at every
// distance and size, so this is geometry saved at equal Q, checked at the PR frames). A
// markdown section for summary.md, and saved.png along the path.
std::string table_7_4_note(const std::vector<ModeSummary>& modes,
                           const std::function<const ModeSummary*(const ModeSummary&)>& cook_of,
                           const std::filesystem::path& plot_file, const std::string& label) {
  std::ostringstream md;
  Plot p;
  p.title = "leaves saved against Cook per frame (" + label + ")";
  p.x_label = "time along the path (s)";
  p.y_label = "saved (%)";
  p.width = 900;
  for (const ModeSummary& m : modes) {
    const ModeSummary* cook = cook_of(m);
    // Modes that aim at Cook's quality: not full, not target (its own Q), not with occlusion.
    if (!cook || cook == &m || m.mode.prune_mode == PruneMode::full || m.mode.prune_mode == PruneMode::target ||
        m.mode.occlusion)
      continue;
    PerFrameVsCook v = per_frame_vs_cook(m, *cook);
    if (v.saved.empty()) continue;
    if (p.series.empty())
      md << "\nPer frame against " << cook->mode.name << " (Neubert 2012 Table 7.4, Fig 7.17: saved.png): leaves saved, "
         << "and the worst Q − Q_Cook over the PR frames (equal Q: >= -" << tolerance_text() << ")\n\n"
         << "| mode | mean saved | min | max | worst Q − Q_Cook | PR frames |\n|---|---|---|---|---|---|\n";
    char row[256];
    std::snprintf(row, sizeof row, "| %s | %.1f %% | %.1f %% | %.1f %% | %+.4f | %u |\n", m.mode.name.c_str(), 100 * v.mean,
                  100 * v.min, 100 * v.max, v.pr_frames ? v.worst_q_delta : 0.0, v.pr_frames);
    md << row;
    PlotSeries s;
    s.label = m.mode.name;
    s.color = mode_color(m.mode.name);
    for (auto [t, saved] : v.saved) s.points.push_back({t, 100.0f * saved});
    p.series.push_back(std::move(s));
  }
  if (p.series.empty()) return "";
  p.x_range = padded_range(p.series, 0, 0.0f);
  p.y_range = padded_range(p.series, 1);
  write_plot(p, plot_file);
  return md.str();
}

void write_path_plot(const std::vector<ModeSummary>& modes, const std::string& title, const std::string& y_label,
                     double (*value)(const BenchFrame&), const std::filesystem::path& file) {
  Plot p;
  p.title = title;
  p.x_label = "time along the path (s)";
  p.y_label = y_label;
  p.width = 900;
  for (const ModeSummary& m : modes) {
    PlotSeries s;
    s.label = m.mode.name;
    s.color = mode_color(m.mode.name);
    for (const BenchFrame& f : m.frames) s.points.push_back({float(f.time), float(value(f))});
    p.series.push_back(std::move(s));
  }
  p.x_range = padded_range(p.series, 0, 0.0f);
  p.y_range = padded_range(p.series, 1);
  p.y_range.x = 0.0f;
  write_plot(p, file);
}

}  // namespace forest::app
