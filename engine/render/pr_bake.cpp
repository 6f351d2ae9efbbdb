#include "engine/render/pr_bake.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <glm/gtc/constants.hpp>

#include "engine/render/contact_sheet.h"
#include "prune_math.h"

namespace forest {

std::vector<float> non_increasing(std::vector<float> v) {
  // Blocks of (sum, count); merge while a block's mean exceeds its predecessor's.
  std::vector<std::pair<double, int>> blocks;
  for (float x : v) {
    blocks.push_back({x, 1});
    while (blocks.size() > 1) {
      auto& b = blocks[blocks.size() - 1];
      auto& a = blocks[blocks.size() - 2];
      if (a.first / a.second >= b.first / b.second) break;
      a.first += b.first, a.second += b.second;
      blocks.pop_back();
    }
  }
  size_t i = 0;
  for (auto& [sum, n] : blocks)
    for (int k = 0; k < n; ++k) v[i++] = float(sum / n);
  return v;
}

PrMeasurement measure_pr_tables(vk::Context& ctx, const TreeModel& model, const PrBakeOptions& options) {
  Scene scene = make_model_scene(model, options.resolution, 1);
  Renderer renderer(ctx, scene, options.resolution, options.resolution, 1);

  // Every (λ, s) to measure, fixed up front: each view renders its reference once.
  std::vector<std::pair<float, float>> points;
  std::vector<float> lambdas(S_SAMPLES);
  for (uint32_t i = 0; i < S_SAMPLES; ++i) lambdas[i] = float(i) / float(S_SAMPLES - 1);
  for (uint32_t i = 1; i < S_SAMPLES; ++i) {
    float l = lambdas[i], top = std::max(1.5f / l, 1.0f);
    for (uint32_t j = 0; j < options.scale_candidates; ++j) {
      float t = options.scale_candidates > 1 ? float(j) / float(options.scale_candidates - 1) : 0.0f;
      points.push_back({l, std::exp(t * std::log(top))});
    }
    points.push_back({l, 1.0f / l});
  }
  std::vector<float> cook(D_SAMPLES);
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    cook[j] = prune::lambda_cook(prune::d_sample(j));
    if (cook[j] > 0.0f) points.push_back({cook[j], 1.0f / cook[j]});
  }

  std::map<std::pair<float, float>, PrResult> sums;
  size_t done = 0, total = size_t(options.views) * points.size();
  for (uint32_t v = 0; v < options.views; ++v) {
    float azimuth = 2.0f * glm::pi<float>() * float(v) / float(options.views);
    float elevation = glm::radians(v % 2 ? 35.0f : 10.0f);
    CameraDesc cam = orbit_camera(model.bounding_sphere, azimuth, elevation, 30.0f);
    FrameSettings full;
    full.prune_mode = PRUNE_FULL;
    renderer.render_reference(cam, full);
    for (auto [l, s] : points) {
      FrameSettings test;
      test.prune_mode = PRUNE_FIXED;
      test.fixed_lambda = l;
      test.fixed_scale = s;
      sums[{l, s}] += renderer.compare_with_reference(cam, test);
      if (options.progress && ++done % 16 == 0) options.progress(double(done) / double(total));
    }
  }

  PrMeasurement out;
  for (auto& [key, pr] : sums) out.samples.push_back({key.first, key.second, pr});
  PrTables& t = out.tables;
  t.views = int(options.views);
  t.resolution = int(options.resolution);
  t.lambda = lambdas;
  t.s_opt.assign(S_SAMPLES, 1.0f);
  t.q_opt.assign(S_SAMPLES, 1.0f);
  t.q_inverse.assign(S_SAMPLES, 1.0f);
  for (uint32_t i = 1; i < S_SAMPLES; ++i) {
    float l = lambdas[i];
    double best = -2.0;
    for (auto& [key, pr] : sums) {
      if (key.first != l) continue;
      double q = pr.quality();
      if (q > best || (q == best && key.second < t.s_opt[i])) best = q, t.s_opt[i] = key.second;
      if (key.second == 1.0f / l) t.q_inverse[i] = float(q);
    }
    t.q_opt[i] = float(best);
  }
  // s must not pop as λ changes: non-increasing in λ, exactly 1 at full detail, and λ = 0
  // (nothing drawn) borrows its neighbour's value.
  t.s_opt[0] = t.s_opt[1];
  t.s_opt = non_increasing(t.s_opt);
  t.s_opt[S_SAMPLES - 1] = 1.0f;
  t.q_opt[0] = 0.0f;
  t.q_inverse[0] = 0.0f;

  // λ_opt(d): the smallest λ whose optimal quality matches Cook's at λ_Cook(d) (§7.2.5).
  auto q_opt_at = [&](float l) {
    float pos = std::clamp(l, 0.0f, 1.0f) * float(S_SAMPLES - 1);
    uint32_t i = std::min(uint32_t(pos), uint32_t(S_SAMPLES - 2));
    float f = pos - float(i);
    return t.q_opt[i] * (1.0f - f) + t.q_opt[i + 1] * f;
  };
  t.d.resize(D_SAMPLES);
  t.lambda_cook = cook;
  t.lambda_opt.resize(D_SAMPLES);
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    t.d[j] = prune::d_sample(j);
    float lc = cook[j];
    if (lc <= 0.0f) {
      t.lambda_opt[j] = 0.0f;
      continue;
    }
    double target = sums[{lc, 1.0f / lc}].quality();
    float found = lc;
    for (int step = 0; step <= 1000; ++step) {
      float l = float(step) / 1000.0f;
      if (l >= lc) break;
      if (q_opt_at(l) >= target) {
        found = l;
        break;
      }
    }
    t.lambda_opt[j] = found;
  }
  t.lambda_opt[0] = 1.0f;
  t.lambda_opt = non_increasing(t.lambda_opt);
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace forest
