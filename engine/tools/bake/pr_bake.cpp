#include "engine/tools/bake/pr_bake.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include <glm/gtc/constants.hpp>

#include "engine/scene/camera.h"
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
  // Once polishing, m is the best of everything measured on this grid, the other sizes'
  // probes included (every render counts every size, so they come free).
  void adopt_best() {
    if (lo < hi) return;
    for (int i = 0; i < int(s.size()); ++i)
      if (!std::isnan(q[size_t(i)]) && better(i, m)) m = i;
    lo = hi = m;
  }
};

using clock = std::chrono::steady_clock;

double seconds_since(clock::time_point t0) { return std::chrono::duration<double>(clock::now() - t0).count(); }

std::vector<CameraDesc> pr_views(const TreeModel& model, const PrBakeOptions& options) {
  return forest::pr_views(model.bounding_sphere, options.views, options.size0, pr_render_resolution(options.size0));
}

// PR of (λ, s) points summed over the views, at every size, each point measured once.
struct PrMeter {
  Renderer& renderer;
  const PrBakeOptions& options;
  std::map<Point, PrSizes> sums;
  std::map<Point, std::array<PrSizes, 2>> folds;  // the same sums over each half of the views
  std::map<Point, std::array<float, PR_SIZES>> low;  // low quantile of Q over views and phases
  PrBakeStats stats;
  size_t expected = 0, measured = 0;  // points, for the progress fraction
};

// Views [0, views/2) and the rest: both halves see both elevations (pr_views alternates them).
uint32_t view_fold(uint32_t view, uint32_t views) { return views > 1 && view >= views / 2 ? 1 : 0; }

// Q of every single render in one bake render: size 0 itself, and each sub-pixel phase of the
// smaller sizes where anything is covered.
void add_single_qualities(std::array<std::vector<float>, PR_SIZES>& q, const PrSizes& sizes, const PrPhases& phases) {
  if (sizes[0].tp + sizes[0].fp + sizes[0].fn > 0) q[0].push_back(float(sizes[0].quality()));
  for (uint32_t b = 1; b < PR_SIZES; ++b)
    for (uint32_t k = prune::phase_bin(b, 0, 0); k < prune::phase_bin(b + 1, 0, 0); ++k)
      if (phases[k].tp + phases[k].fp + phases[k].fn > 0) q[b].push_back(float(phases[k].quality()));
}

// Measures the points not measured yet (duplicates once): all views of all points in one
// submit (Renderer::compare_coverage).
void measure(PrMeter& m, std::vector<Point> points) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::erase_if(points, [&](const Point& p) { return m.sums.count(p) > 0; });
  if (points.empty()) return;
  std::vector<CoverageJob> jobs;
  for (auto [l, s] : points)
    for (uint32_t v = 0; v < m.options.views; ++v) jobs.push_back({v, l, s});
  auto t0 = clock::now();
  std::vector<PrPhases> phases;
  std::vector<PrSizes> r = m.renderer.compare_coverage(jobs, &phases);
  m.stats.compare_seconds += seconds_since(t0);
  ++m.stats.submits;
  // Q of each view (and phase), per elevation (pr_views alternates two).
  std::map<Point, std::array<std::array<std::vector<float>, PR_SIZES>, 2>> single;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const Point key{jobs[i].lambda, jobs[i].scale};
    PrSizes& sum = m.sums[key];
    PrSizes& fold = m.folds[key][view_fold(jobs[i].view, m.options.views)];
    for (uint32_t b = 0; b < PR_SIZES; ++b) sum[b] += r[i][b], fold[b] += r[i][b];
    add_single_qualities(single[key][jobs[i].view % 2], r[i], phases[i]);
  }
  // The lower of the two elevations' quantiles: trees seen from near the ground (frames'
  // usual view) lose more than those seen from above, and a pooled quantile hid that.
  for (auto& [key, q] : single)
    for (uint32_t b = 0; b < PR_SIZES; ++b) m.low[key][b] = std::min(low_quantile(std::move(q[0][b])), low_quantile(std::move(q[1][b])));
  m.stats.renders += uint32_t(points.size()) * m.options.views;
  m.measured += points.size();
  if (m.options.progress)
    m.options.progress(std::min(0.99, double(m.measured) / double(std::max(m.expected, m.measured + 1))));
}

ScaleSearch start_search(float lambda, uint32_t candidates) {
  ScaleSearch ss;
  ss.lambda = lambda;
  ss.s = scale_grid(ss.lambda, candidates);
  ss.q.assign(ss.s.size(), std::nan(""));
  ss.hi = int(ss.s.size()) - 1;
  ss.m = int(std::find(ss.s.begin(), ss.s.end(), 1.0f / ss.lambda) - ss.s.begin());
  return ss;
}

// The sample positions of the tables, the points measured first and one s search per λ > 0
// and searched size.
struct SamplePlan {
  std::vector<float> lambdas;  // S_SAMPLES
  std::vector<float> far;      // F_SAMPLES: the far λ below lambdas[1]
  std::vector<float> cook;     // D_SAMPLES: λ_Cook(d_j)
  std::vector<Point> first;    // Cook's points, and the start of every s search (or the whole grid)
  std::vector<ScaleSearch> searches;
  std::vector<uint32_t> search_size;  // the size each search maximizes Q at
  size_t expected = 0;         // points measured in all, about (for progress)
};

SamplePlan plan_samples(const PrBakeOptions& options) {
  SamplePlan plan;
  plan.lambdas.resize(S_SAMPLES);
  for (uint32_t i = 0; i < S_SAMPLES; ++i) plan.lambdas[i] = pr_lambda(i);  // the tables' sample positions
  plan.cook.resize(D_SAMPLES);
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    plan.cook[j] = pr_lambda_cook(j);
    if (plan.cook[j] > 0.0f) plan.first.push_back({plan.cook[j], 1.0f / plan.cook[j]});
  }
  for (uint32_t f = 0; f < F_SAMPLES; ++f) plan.far.push_back(pr_lambda_far(f));
  const uint32_t searched = options.searched_sizes & ((1u << PR_SIZES) - 1u);
  std::vector<float> searched_lambdas(plan.lambdas.begin() + 1, plan.lambdas.end());
  searched_lambdas.insert(searched_lambdas.end(), plan.far.begin(), plan.far.end());
  for (float lambda : searched_lambdas) {
    ScaleSearch ss = start_search(lambda, options.scale_candidates);
    plan.first.push_back({ss.lambda, 1.0f / ss.lambda});  // Cook's s = 1/λ is always measured (q_inverse)
    if (!options.search_scale)
      for (float s : ss.s) plan.first.push_back({ss.lambda, s});
    // The sizes' searches share most probes (each render counts every size).
    plan.expected += options.search_scale ? 3 * size_t(std::ceil(std::log2(double(ss.s.size())))) : ss.s.size();
    if (options.search_scale)
      for (uint32_t b = 0; b < PR_SIZES; ++b) {
        if ((searched & (1u << b)) == 0) continue;
        plan.searches.push_back(ss);
        plan.search_size.push_back(b);
      }
  }
  plan.expected += D_SAMPLES;
  return plan;
}

// Every search starts from Cook's s = 1/λ (measured with the first points); then all
// searches' probes of a round are measured together until none asks for more.
void run_scale_searches(PrMeter& m, SamplePlan& plan) {
  std::vector<ScaleSearch>& searches = plan.searches;
  auto quality = [&](size_t k, int p) {
    return m.sums[{searches[k].lambda, searches[k].s[size_t(p)]}][plan.search_size[k]].quality();
  };
  for (size_t k = 0; k < searches.size(); ++k) searches[k].q[size_t(searches[k].m)] = quality(k, searches[k].m);
  for (;;) {
    std::vector<Point> round;
    std::vector<std::vector<int>> probes;
    for (size_t k = 0; k < searches.size(); ++k) {
      ScaleSearch& ss = searches[k];
      for (size_t i = 0; i < ss.s.size(); ++i)
        if (std::isnan(ss.q[i]) && m.sums.count({ss.lambda, ss.s[i]})) ss.q[i] = quality(k, int(i));
      ss.adopt_best();
      probes.push_back(ss.probes());
      for (int p : probes.back()) round.push_back({ss.lambda, ss.s[size_t(p)]});
    }
    if (round.empty()) break;
    measure(m, round);
    for (size_t k = 0; k < searches.size(); ++k) {
      if (probes[k].empty()) continue;
      for (int p : probes[k]) searches[k].q[size_t(p)] = quality(k, p);
      searches[k].advance(probes[k]);
    }
  }
}

// s_opt(λ) (ties to the smaller s), q_opt and q_inverse at size b from the measured points.
// q_opt is not the best pooled Q itself: the maximum over a dozen s values of a Q that one
// pixel moves by 0.005–0.03 at small sizes is biased upward (the winner's curse), and λ_opt
// came out too small by that bias. So each half of the views chooses its s and is measured
// at the other half's choice (two-fold cross-fitting); where that held-out Q does not beat
// Cook's s = 1/λ, s_opt is Cook's.
struct ScaleChoice {
  float s = 1.0f;
  float q = 1.0f, q_inverse = 1.0f;
  float q_low = 1.0f;  // at s
};

ScaleChoice choose_scale(const PrMeter& m, float l, uint32_t b) {
  struct Best {
    double q = -2.0;
    float s = 0.0f;
    void offer(double qs, float ss) {
      if (qs > q || (qs == q && ss < s)) q = qs, s = ss;
    }
  } pooled, half[2];
  ScaleChoice c;
  for (auto& [key, pr] : m.sums) {
    if (key.first != l) continue;
    pooled.offer(pr[b].quality(), key.second);
    for (int f = 0; f < 2; ++f) half[f].offer(m.folds.at(key)[size_t(f)][b].quality(), key.second);
    if (key.second == 1.0f / l) c.q_inverse = float(pr[b].quality());
  }
  c.s = pooled.s;
  c.q = float(pooled.q);
  if (m.options.views >= 2) {
    PrResult held = m.folds.at({l, half[0].s})[1][b];
    held += m.folds.at({l, half[1].s})[0][b];
    c.q = float(held.quality());
    if (c.q <= c.q_inverse) c.s = 1.0f / l, c.q = c.q_inverse;
  }
  c.q_low = m.low.at({l, c.s})[b];
  return c;
}

void fill_scale_tables(PrSizeTables& t, const PrMeter& m, const SamplePlan& plan, uint32_t b) {
  // s_opt, q_opt, q_inverse and q_low at `lambdas` (those before `first` stay 1).
  auto fill = [&](const std::vector<float>& lambdas, size_t first, std::vector<float>& s, std::vector<float>& q,
                  std::vector<float>& q_inverse, std::vector<float>& q_low) {
    for (std::vector<float>* v : {&s, &q, &q_inverse, &q_low}) v->assign(lambdas.size(), 1.0f);
    for (size_t i = first; i < lambdas.size(); ++i) {
      ScaleChoice c = choose_scale(m, lambdas[i], b);
      s[i] = c.s, q[i] = c.q, q_inverse[i] = c.q_inverse, q_low[i] = c.q_low;
    }
  };
  fill(plan.lambdas, 1, t.s_opt, t.q_opt, t.q_inverse, t.q_low);
  fill(plan.far, 0, t.s_far, t.q_far, t.q_inverse_far, t.q_low_far);
  // s must not pop as λ changes: non-increasing in λ over the far and the regular samples,
  // exactly 1 at full detail, and λ = 0 (nothing drawn) borrows its neighbour's value.
  std::vector<float> ascending(t.s_far.rbegin(), t.s_far.rend());
  ascending.insert(ascending.end(), t.s_opt.begin() + 1, t.s_opt.end());
  ascending = non_increasing(ascending);
  for (uint32_t f = 0; f < F_SAMPLES; ++f) t.s_far[f] = ascending[F_SAMPLES - 1 - f];
  std::copy(ascending.begin() + F_SAMPLES, ascending.end(), t.s_opt.begin() + 1);
  t.s_opt[0] = t.s_opt[1];
  t.s_opt[S_SAMPLES - 1] = 1.0f;
  t.q_opt[0] = 0.0f;
  t.q_inverse[0] = 0.0f;
  t.q_low[0] = 0.0f;
}

// λ_opt(d) at size b: the smallest λ whose optimal quality matches Cook's at λ_Cook(d)
// (Neubert 2012 §7.2.5), both seen at that size. Where λ_Cook(d) is below the first measured
// λ (1/20), q_opt there would be a straight line to Q = 0 at λ = 0, a guess: λ_opt = λ_Cook, and
// the run time's s goes over to Cook's 1/λ (tree_detail.glsl), so opt is Cook there. For the
// same reason λ_opt does not go below 1/20 while λ_Cook(d) is above it.
void fill_lambda_opt(PrSizeTables& t, std::map<Point, PrSizes>& sums, const std::vector<float>& cook, uint32_t b) {
  t.lambda_opt.resize(D_SAMPLES);
  for (uint32_t j = 0; j < D_SAMPLES; ++j) {
    float lc = cook[j];
    t.lambda_opt[j] = lc < pr_lambda(1) ? std::min(lc, j > 0 ? t.lambda_opt[j - 1] : lc)
                                        : std::max(pr_lambda(1), smallest_lambda_reaching(t.q_opt, sums[{lc, 1.0f / lc}][b].quality(), lc));
  }
  t.lambda_opt[0] = 1.0f;
  t.lambda_opt = non_increasing(t.lambda_opt);
}

}  // namespace

uint32_t pr_render_resolution(uint32_t size0) { return size0 + 4; }

std::vector<CameraDesc> pr_views(glm::vec4 sphere, uint32_t views, uint32_t size, uint32_t resolution) {
  std::vector<CameraDesc> cams;
  for (uint32_t v = 0; v < views; ++v) {  // azimuths around the model, alternating two elevations
    float azimuth = 2.0f * glm::pi<float>() * float(v) / float(views);
    float elevation = glm::radians(v % 2 ? 35.0f : 10.0f);
    cams.push_back(pr_view_camera(sphere, azimuth, elevation, size, resolution));
  }
  return cams;
}

CameraDesc pr_view_camera(glm::vec4 sphere, float azimuth, float elevation, uint32_t size0, uint32_t resolution) {
  CameraDesc cam;
  cam.fov_deg = 30.0f;
  // prune::projected_size(r, D, k) = size0 with k = the frame's focal length in pixels.
  const float r = std::max(sphere.w, 1e-3f);
  const float k = focal_pixels(float(resolution), cam.fov_deg);
  const float along = 2.0f * k * r / float(size0);  // √(D² − r²)
  const float distance = std::sqrt(along * along + r * r);
  cam.target = glm::vec3(sphere);
  cam.position = cam.target + distance * glm::vec3(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                                   -std::cos(azimuth) * std::cos(elevation));
  cam.near = std::max(distance * 1e-3f, 1e-3f);
  cam.far = distance * 4.0f;
  return cam;
}

PrMeasurement measure_pr_tables(vk::Context& ctx, const TreeModel& model, const PrBakeOptions& options) {
  const uint32_t resolution = pr_render_resolution(options.size0);
  Scene scene = make_model_scene(model, resolution, 1);
  // The bark at the branch LOD a scene's frame draws (its default error), at every size
  // (coverage_batch.cpp), not the preview's full detail: frames prune leaves around that bark.
  scene.desc.lod_error_pixels = SceneDesc{}.lod_error_pixels;
  Renderer renderer(ctx, scene, resolution, resolution, 1);
  PrMeter meter{renderer, options};
  auto t0 = clock::now();
  renderer.set_coverage_views(pr_views(model, options));  // the views' full-detail (and branch) coverage, once
  meter.stats.reference_seconds += seconds_since(t0);
  ++meter.stats.submits;
  SamplePlan plan = plan_samples(options);
  meter.expected = plan.expected;
  measure(meter, plan.first);
  run_scale_searches(meter, plan);

  PrMeasurement out;
  out.stats = meter.stats;
  for (auto& [key, pr] : meter.sums) out.samples.push_back({key.first, key.second, pr});
  PrTables& t = out.tables;
  t.views = int(options.views);
  t.resolution = int(resolution);
  t.size0 = float(options.size0);
  t.sizes.resize(PR_SIZES);
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    fill_scale_tables(t.sizes[b], meter, plan, b);
    fill_lambda_opt(t.sizes[b], meter.sums, plan.cook, b);
  }
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace forest
