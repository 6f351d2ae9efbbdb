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

  // PR diagram (Fig 7.2): for a few λ, the (R, P) points over the scales tried.
  std::map<float, std::vector<std::pair<float, glm::vec2>>> by_lambda;  // λ -> (s, (R, P))
  for (const PrPoint& s : model.bake.pr_samples)
    by_lambda[s.lambda].push_back({s.scale, {float(s.recall), float(s.precision)}});
  Plot pr{"PR diagram: " + name, "recall", "precision", {0, 1}, {0, 1}, {}};
  std::string samples_csv = "lambda,s,precision,recall\n";
  const float shown[] = {0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 0.9f};
  for (auto& [l, points] : by_lambda) {
    std::sort(points.begin(), points.end(), [](auto& a, auto& b) { return a.first < b.first; });
    for (auto& [s, rp] : points)
      samples_csv += std::to_string(l) + "," + std::to_string(s) + "," + std::to_string(rp.y) + "," + std::to_string(rp.x) + "\n";
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

  // s vs λ (Fig 7.9) with Cook's 1/λ.
  Plot sp{"leaf area scale: " + name, "lambda", "s", {0, 1}, {0, 12}, {}};
  PlotSeries s_opt{"s_opt (PR)", {}, {0.1f, 0.3f, 0.85f}, true, true}, inv{"1/lambda (Cook)", {}, {0.85f, 0.2f, 0.1f}};
  std::string table_csv = "lambda,s_opt,q_opt,q_inverse\n";
  for (uint32_t i = 0; i < S_SAMPLES; ++i) {
    const float l = pr_lambda(i);
    if (l > 0) s_opt.points.push_back({l, t.s_opt[i]}), inv.points.push_back({l, 1.0f / l});
    table_csv += std::to_string(l) + "," + std::to_string(t.s_opt[i]) + "," + std::to_string(t.q_opt[i]) +
                 "," + std::to_string(t.q_inverse[i]) + "\n";
  }
  sp.series = {s_opt, inv};
  write_plot(sp, dir / "scale_vs_lambda.png");

  // λ(d) (Fig 7.10): optimized vs Cook.
  Plot lp{"detail level vs distance: " + name, "normalized distance d", "lambda", {0, 1}, {0, 1}, {}};
  PlotSeries lo{"lambda_opt", {}, {0.1f, 0.3f, 0.85f}, true, true}, lc{"(1-d)^2 (Cook)", {}, {0.85f, 0.2f, 0.1f}};
  std::string d_csv = "d,lambda_opt,lambda_cook\n";
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    const float d = pr_d(j), cook = pr_lambda_cook(j);
    lo.points.push_back({d, t.lambda_opt[j]});
    lc.points.push_back({d, cook});
    d_csv += std::to_string(d) + "," + std::to_string(t.lambda_opt[j]) + "," + std::to_string(cook) + "\n";
  }
  lp.series = {lo, lc};
  write_plot(lp, dir / "lambda_vs_distance.png");

  write_text_file(dir / "pr_samples.csv", samples_csv);
  write_text_file(dir / "scale_table.csv", table_csv);
  write_text_file(dir / "lambda_table.csv", d_csv);
  std::printf("wrote %s/{pr_diagram,scale_vs_lambda,lambda_vs_distance}.png and 3 CSV files\n", dir.c_str());
  return 0;
}

}  // namespace forest::app
