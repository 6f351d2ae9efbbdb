#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/tools/report/plot.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"

namespace forest::app {

namespace {

glm::vec3 ramp(float t) { return glm::mix(glm::vec3(0.85f, 0.2f, 0.1f), glm::vec3(0.1f, 0.3f, 0.85f), t); }

// The PR diagram (Fig 7.2) at the size nearest 128 px; returns every sample as CSV.
std::string write_pr_diagram(const TreeModel& model, const PrTables& t, const std::string& name,
                             const std::filesystem::path& dir) {
  uint32_t shown_size = 0;
  for (uint32_t b = 0; b < PR_SIZES; ++b)
    if (std::abs(std::log2(pr_size(t.size0, b) / 128.0f)) < std::abs(std::log2(pr_size(t.size0, shown_size) / 128.0f)))
      shown_size = b;
  const float diagram_size = pr_size(t.size0, shown_size);
  std::map<float, std::vector<std::pair<float, glm::vec2>>> by_lambda;  // λ -> (s, (R, P))
  std::string samples_csv = "lambda,s,size_px,precision,recall\n";
  for (const PrPoint& s : model.bake.pr_samples) {
    samples_csv += std::to_string(s.lambda) + "," + std::to_string(s.scale) + "," + std::to_string(s.size) + "," +
                   std::to_string(s.precision) + "," + std::to_string(s.recall) + "\n";
    if (s.size == diagram_size) by_lambda[s.lambda].push_back({s.scale, {float(s.recall), float(s.precision)}});
  }
  char title[160];
  std::snprintf(title, sizeof(title), "PR diagram at %g px: %s", double(diagram_size), name.c_str());
  Plot pr{title, "recall", "precision", {0, 1}, {0, 1}, {}};
  const float shown[] = {0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 0.9f};
  for (auto& [l, points] : by_lambda) {
    std::sort(points.begin(), points.end(), [](auto& a, auto& b) { return a.first < b.first; });
    for (float want : shown)
      if (std::abs(l - want) < 1e-4f) {
        PlotSeries series{"lambda " + std::to_string(want).substr(0, 3), {}, ramp(want), true, true};
        for (auto& [s, rp] : points) series.points.push_back(rp);
        pr.series.push_back(series);
      }
  }
  pr.x_range = padded_range(pr.series, 0);
  pr.y_range = padded_range(pr.series, 1);
  pr.x_range.y = pr.y_range.y = 1.0f;
  write_plot(pr, dir / "pr_diagram.png");

  return samples_csv;
}

}  // namespace

int run_report(const ReportArgs& args) {
  TreeModel model = load_glb(args.model);
  const std::optional<PrTables>& tables = model.bake.pr_tables;  // validated by load_glb
  if (!tables) throw InputError(args.model, 0, "extras.forest.pr_tables", "model is not baked (run forest bake first)");
  std::filesystem::path dir = args.out;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create folder: " + ec.message());
  const PrTables& t = *tables;
  std::string name = model.meta.value("species", std::filesystem::path(args.model).stem().string());

  std::string samples_csv = write_pr_diagram(model, t, name, dir);

  auto size_label = [&](uint32_t b) {
    char l[32];
    std::snprintf(l, sizeof(l), "%g px", double(pr_size(t.size0, b)));
    return std::string(l);
  };
  // s vs λ (Fig 7.9) per projected size, with Cook's 1/λ.
  Plot sp{"leaf area scale: " + name, "lambda", "s", {0, 1}, {0, 12}, {}};
  PlotSeries inv{"1/lambda (Cook)", {}, {0.2f, 0.2f, 0.2f}};
  std::string table_csv = "size_px,lambda,s_opt,q_opt,q_inverse,q_low\n";
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const PrSizeTables& st = t.sizes[b];
    PlotSeries s_opt{"s_opt at " + size_label(b), {}, ramp(float(b) / float(PR_SIZES - 1)), true, true};
    for (uint32_t f = F_SAMPLES; f-- > 0;) {  // the far samples below 1/20, ascending λ
      const float l = pr_lambda_far(f);
      s_opt.points.push_back({l, st.s_far[f]});
      table_csv += std::to_string(pr_size(t.size0, b)) + "," + std::to_string(l) + "," + std::to_string(st.s_far[f]) +
                   "," + std::to_string(st.q_far[f]) + "," + std::to_string(st.q_inverse_far[f]) + "," +
                   std::to_string(st.q_low_far[f]) + "\n";
    }
    for (uint32_t i = 0; i < S_SAMPLES; ++i) {
      const float l = pr_lambda(i);
      if (l > 0) s_opt.points.push_back({l, st.s_opt[i]});
      if (l > 0 && b == 0) inv.points.push_back({l, 1.0f / l});
      table_csv += std::to_string(pr_size(t.size0, b)) + "," + std::to_string(l) + "," + std::to_string(st.s_opt[i]) +
                   "," + std::to_string(st.q_opt[i]) + "," + std::to_string(st.q_inverse[i]) + "," + std::to_string(st.q_low[i]) + "\n";
    }
    sp.series.push_back(s_opt);
  }
  sp.series.push_back(inv);
  write_plot(sp, dir / "scale_vs_lambda.png");

  // λ(d) (Fig 7.10) per projected size: optimized vs Cook.
  Plot lp{"detail level vs distance: " + name, "normalized distance d", "lambda", {0, 1}, {0, 1}, {}};
  PlotSeries lc{"(1-d)^2 (Cook)", {}, {0.2f, 0.2f, 0.2f}};
  std::string d_csv = "size_px,d,lambda_opt,lambda_cook\n";
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    PlotSeries lo{"lambda_opt at " + size_label(b), {}, ramp(float(b) / float(PR_SIZES - 1)), true, true};
    for (uint32_t j = 0; j < D_SAMPLES; ++j) {
      const float d = pr_d(j), cook = pr_lambda_cook(j);
      lo.points.push_back({d, t.sizes[b].lambda_opt[j]});
      if (b == 0) lc.points.push_back({d, cook});
      d_csv += std::to_string(pr_size(t.size0, b)) + "," + std::to_string(d) + "," +
               std::to_string(t.sizes[b].lambda_opt[j]) + "," + std::to_string(cook) + "\n";
    }
    lp.series.push_back(lo);
  }
  lp.series.push_back(lc);
  write_plot(lp, dir / "lambda_vs_distance.png");

  write_text_file(dir / "pr_samples.csv", samples_csv);
  write_text_file(dir / "scale_table.csv", table_csv);
  write_text_file(dir / "lambda_table.csv", d_csv);
  std::printf("wrote %s/{pr_diagram,scale_vs_lambda,lambda_vs_distance}.png and 3 CSV files\n", dir.c_str());
  return 0;
}

}  // namespace forest::app
