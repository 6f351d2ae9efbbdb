#include "engine/tools/bake/pr_bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <glm/gtc/constants.hpp>

#include "engine/tools/gallery/contact_sheet.h"
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

std::vector<float> scale_grid(float lambda, uint32_t candidates) {
  std::vector<float> s;
  float top = std::max(1.5f / lambda, 1.0f);
  for (uint32_t j = 0; j < candidates; ++j) {
    float t = candidates > 1 ? float(j) / float(candidates - 1) : 0.0f;
    s.push_back(std::exp(t * std::log(top)));
  }
  s.push_back(1.0f / lambda);
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  return s;
}

float smallest_lambda_reaching(const std::vector<float>& q_opt, double target, float upper) {
  const uint32_t n = uint32_t(q_opt.size());
  auto q_opt_at = [&](float l) {
    float pos = std::clamp(l, 0.0f, 1.0f) * float(n - 1);
    uint32_t i = std::min(uint32_t(pos), n - 2);
    float f = pos - float(i);
    return q_opt[i] * (1.0f - f) + q_opt[i + 1] * f;
  };
  for (int step = 0; step <= 1000; ++step) {
    float l = float(step) / 1000.0f;
    if (l >= upper) break;
    if (q_opt_at(l) >= target) return l;
  }
  return upper;
}

namespace {

using Point = std::pair<float, float>;  // (λ, s)

// Search for the best s on one λ's grid, assuming Q unimodal in s (it trades recall for
// precision). Bracket phase: [lo, hi] holds the maximum, m is the best index measured so
// far; a probe at the middle of the larger side either becomes m (the bracket closes on
// its side of the old m) or moves that bracket end past itself. Q is flat near its maximum
// and measured with pixel noise, so a converged m is then polished: every grid value within
// kPolish steps is measured and m moves to the best of them until it stays.
struct ScaleSearch {
  static constexpr int kPolish = 2;
  float lambda = 0;
  std::vector<float> s;
  std::vector<double> q;  // NaN until measured
  int lo = 0, hi = 0, m = 0;

  // Ties go to the smaller s, as in the exhaustive choice.
  bool better(int a, int b) const { return q[a] > q[b] || (q[a] == q[b] && a < b); }
  // Grid indices to measure next; empty when the search is over.
  std::vector<int> probes() const {
    if (lo < hi) {
      int left = m - lo, right = hi - m;
      return {left >= right ? lo + (left - 1) / 2 : m + 1 + (right - 1) / 2};
    }
    std::vector<int> out;
    for (int i = std::max(0, m - kPolish); i <= std::min(int(s.size()) - 1, m + kPolish); ++i)
      if (std::isnan(q[size_t(i)])) out.push_back(i);
    return out;
  }
  // After the qualities of `probes()` are in q.
  void advance(const std::vector<int>& measured) {
    if (lo < hi) {
      int p = measured[0];
      if (better(p, m) && p < m) hi = m - 1, m = p;
      else if (better(p, m)) lo = m + 1, m = p;
      else if (p < m) lo = p + 1;
      else hi = p - 1;
      return;
    }
    for (int i : measured)
      if (better(i, m)) m = i;
    lo = hi = m;
  }
};

}  // namespace

PrMeasurement measure_pr_tables(vk::Context& ctx, const TreeModel& model, const PrBakeOptions& options) {
  using clock = std::chrono::steady_clock;
  Scene scene = make_model_scene(model, options.resolution, 1);
  Renderer renderer(ctx, scene, options.resolution, options.resolution, 1);
  PrBakeStats stats;

  std::vector<CameraDesc> cams;
  for (uint32_t v = 0; v < options.views; ++v) {
    float azimuth = 2.0f * glm::pi<float>() * float(v) / float(options.views);
    float elevation = glm::radians(v % 2 ? 35.0f : 10.0f);
    cams.push_back(orbit_camera(model.bounding_sphere, azimuth, elevation, 30.0f));
  }
  if (options.batched) {
    auto t0 = clock::now();
    renderer.set_coverage_views(cams);
    stats.reference_seconds += std::chrono::duration<double>(clock::now() - t0).count();
    ++stats.submits;
  }

  // PR of (λ, s) points summed over the views, measured once each.
  std::map<Point, PrResult> sums;
  size_t expected = 0, measured = 0;
  auto measure = [&](std::vector<Point> points) {
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    std::erase_if(points, [&](const Point& p) { return sums.count(p) > 0; });
    if (points.empty()) return;
    if (options.batched) {
      std::vector<CoverageJob> jobs;
      for (auto [l, s] : points)
        for (uint32_t v = 0; v < options.views; ++v) jobs.push_back({v, l, s});
      auto t0 = clock::now();
      std::vector<PrResult> r = renderer.compare_coverage(jobs);
      stats.compare_seconds += std::chrono::duration<double>(clock::now() - t0).count();
      ++stats.submits;
      for (size_t i = 0; i < jobs.size(); ++i) sums[{jobs[i].lambda, jobs[i].scale}] += r[i];
    } else {
      for (uint32_t v = 0; v < options.views; ++v) {
        auto t0 = clock::now();
        FrameSettings full;
        full.prune_mode = PRUNE_FULL;
        renderer.render_reference(cams[v], full);
        auto t1 = clock::now();
        for (auto [l, s] : points) {
          FrameSettings test;
          test.prune_mode = PRUNE_FIXED;
          test.fixed_lambda = l;
          test.fixed_scale = s;
          sums[{l, s}] += renderer.compare_with_reference(cams[v], test);
        }
        stats.reference_seconds += std::chrono::duration<double>(t1 - t0).count();
        stats.compare_seconds += std::chrono::duration<double>(clock::now() - t1).count();
        stats.submits += 1 + uint32_t(points.size());
      }
    }
    stats.renders += uint32_t(points.size()) * options.views;
    measured += points.size();
    if (options.progress) options.progress(std::min(0.99, double(measured) / double(std::max(expected, measured + 1))));
  };

  std::vector<float> lambdas(S_SAMPLES);
  for (uint32_t i = 0; i < S_SAMPLES; ++i) lambdas[i] = float(i) / float(S_SAMPLES - 1);
  std::vector<float> cook(D_SAMPLES);
  std::vector<Point> first;  // Cook's points, and the start of every s search (or the whole grid)
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    cook[j] = prune::lambda_cook(prune::d_sample(j));
    if (cook[j] > 0.0f) first.push_back({cook[j], 1.0f / cook[j]});
  }
  std::vector<ScaleSearch> searches;
  for (uint32_t i = 1; i < S_SAMPLES; ++i) {
    ScaleSearch ss;
    ss.lambda = lambdas[i];
    ss.s = scale_grid(ss.lambda, options.scale_candidates);
    ss.q.assign(ss.s.size(), std::nan(""));
    ss.hi = int(ss.s.size()) - 1;
    ss.m = int(std::find(ss.s.begin(), ss.s.end(), 1.0f / ss.lambda) - ss.s.begin());
    first.push_back({ss.lambda, 1.0f / ss.lambda});  // Cook's s = 1/λ is always measured (q_inverse)
    if (!options.search_scale)
      for (float s : ss.s) first.push_back({ss.lambda, s});
    expected += options.search_scale ? 2 * size_t(std::ceil(std::log2(double(ss.s.size())))) : ss.s.size();
    searches.push_back(std::move(ss));
  }
  expected += D_SAMPLES;
  measure(first);
  for (ScaleSearch& ss : searches) ss.q[size_t(ss.m)] = sums[{ss.lambda, ss.s[size_t(ss.m)]}].quality();
  while (options.search_scale) {
    std::vector<Point> round;
    std::vector<std::vector<int>> probes;
    for (ScaleSearch& ss : searches) {
      probes.push_back(ss.probes());
      for (int p : probes.back()) round.push_back({ss.lambda, ss.s[size_t(p)]});
    }
    if (round.empty()) break;
    measure(round);
    for (size_t k = 0; k < searches.size(); ++k) {
      ScaleSearch& ss = searches[k];
      if (probes[k].empty()) continue;
      for (int p : probes[k]) ss.q[size_t(p)] = sums[{ss.lambda, ss.s[size_t(p)]}].quality();
      ss.advance(probes[k]);
    }
  }

  PrMeasurement out;
  out.stats = stats;
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

  // λ_opt(d): the smallest λ whose optimal quality matches Cook's at λ_Cook(d) (Neubert 2012 §7.2.5).
  t.d.resize(D_SAMPLES);
  t.lambda_cook = cook;
  t.lambda_opt.resize(D_SAMPLES);
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    t.d[j] = prune::d_sample(j);
    float lc = cook[j];
    t.lambda_opt[j] = lc <= 0.0f ? 0.0f : smallest_lambda_reaching(t.q_opt, sums[{lc, 1.0f / lc}].quality(), lc);
  }
  t.lambda_opt[0] = 1.0f;
  t.lambda_opt = non_increasing(t.lambda_opt);
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace forest
