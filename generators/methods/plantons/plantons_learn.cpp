#include "generators/methods/plantons/plantons_learn.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "generators/core/input_error.h"
#include "generators/core/rng.h"

namespace forest {

namespace {

double sq_dist(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (size_t k = 0; k < a.size(); ++k) d += (a[k] - b[k]) * (a[k] - b[k]);
  return d;
}

// Renumbers labels in order of first appearance (sample by sample, organ by organ) so that
// equal partitions compare equal and the model's planton order is deterministic.
size_t canonicalize(std::vector<std::vector<uint32_t>>& labels) {
  std::map<uint32_t, uint32_t> remap;
  for (auto& sample : labels)
    for (uint32_t& l : sample) {
      auto [it, fresh] = remap.try_emplace(l, uint32_t(remap.size()));
      l = it->second;
    }
  return remap.size();
}

}  // namespace

std::vector<uint32_t> kmeans(const std::vector<std::vector<double>>& pts, int k, int restarts,
                             uint64_t seed) {
  const size_t n = pts.size();
  if (n == 0) return {};
  k = std::clamp(k, 1, int(n));
  std::vector<uint32_t> best_assign(n, 0);
  double best_cost = std::numeric_limits<double>::infinity();
  for (int r = 0; r < std::max(1, restarts); ++r) {
    Rng rng(hash64(seed, uint64_t(r)), 31);
    // k-means++ seeding.
    std::vector<std::vector<double>> centers{pts[size_t(rng.uniform() * double(n)) % n]};
    std::vector<double> d2(n);
    while (int(centers.size()) < k) {
      double total = 0.0;
      for (size_t i = 0; i < n; ++i) {
        d2[i] = std::numeric_limits<double>::infinity();
        for (const auto& c : centers) d2[i] = std::min(d2[i], sq_dist(pts[i], c));
        total += d2[i];
      }
      if (!(total > 0.0)) break;  // fewer distinct points than k
      double pick = rng.uniform() * total;
      size_t at = n - 1;
      for (size_t i = 0; i < n; ++i) {
        pick -= d2[i];
        if (pick < 0.0) {
          at = i;
          break;
        }
      }
      centers.push_back(pts[at]);
    }
    // Lloyd iterations until the assignment is stable.
    std::vector<uint32_t> assign(n, UINT32_MAX);
    for (int it = 0; it < 200; ++it) {
      bool changed = false;
      for (size_t i = 0; i < n; ++i) {
        uint32_t arg = 0;
        double bd = std::numeric_limits<double>::infinity();
        for (size_t c = 0; c < centers.size(); ++c) {
          double d = sq_dist(pts[i], centers[c]);
          if (d < bd) {
            bd = d;
            arg = uint32_t(c);
          }
        }
        if (assign[i] != arg) changed = true;
        assign[i] = arg;
      }
      if (!changed) break;
      std::vector<std::vector<double>> sum(centers.size(), std::vector<double>(pts[0].size(), 0.0));
      std::vector<size_t> cnt(centers.size(), 0);
      for (size_t i = 0; i < n; ++i) {
        ++cnt[assign[i]];
        for (size_t d = 0; d < pts[i].size(); ++d) sum[assign[i]][d] += pts[i][d];
      }
      for (size_t c = 0; c < centers.size(); ++c)
        if (cnt[c] > 0)
          for (size_t d = 0; d < sum[c].size(); ++d) centers[c][d] = sum[c][d] / double(cnt[c]);
    }
    double cost = 0.0;
    for (size_t i = 0; i < n; ++i) cost += sq_dist(pts[i], centers[assign[i]]);
    if (cost < best_cost) {
      best_cost = cost;
      best_assign = assign;
    }
  }
  return best_assign;
}

double adjusted_rand_index(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
  std::map<std::pair<uint32_t, uint32_t>, double> joint;
  std::map<uint32_t, double> ra, rb;
  for (size_t i = 0; i < a.size(); ++i) {
    joint[{a[i], b[i]}] += 1;
    ra[a[i]] += 1;
    rb[b[i]] += 1;
  }
  auto c2 = [](double x) { return x * (x - 1) / 2; };
  double index = 0, sa = 0, sb = 0;
  for (auto& [k, v] : joint) index += c2(v);
  for (auto& [k, v] : ra) sa += c2(v);
  for (auto& [k, v] : rb) sb += c2(v);
  double expected = sa * sb / c2(double(a.size()));
  double max_index = 0.5 * (sa + sb);
  if (max_index == expected) return 1.0;  // both partitions trivial
  return (index - expected) / (max_index - expected);
}

LearnResult learn_plantons(const std::vector<OrganTree>& samples, const LearnParams& P) {
  size_t total = 0;
  for (const OrganTree& t : samples) total += t.organs.size();
  if (samples.empty() || total == 0) throw InputError("plantons: no sample organs to learn from");
  LearnResult result;
  const FeatureScales scales = feature_scales(samples);

  // k-means per organ type over the pooled organs.
  std::vector<std::vector<uint32_t>> labels(samples.size());
  for (size_t s = 0; s < samples.size(); ++s) labels[s].assign(samples[s].organs.size(), 0);
  uint32_t next_label = 0;
  for (int type = 0; type < kOrganTypes; ++type) {
    std::vector<std::vector<double>> pts;
    std::vector<std::pair<size_t, size_t>> where;
    for (size_t s = 0; s < samples.size(); ++s)
      for (size_t k = 0; k < samples[s].organs.size(); ++k)
        if (int(samples[s].organs[k].type) == type) {
          pts.push_back(to_z(scales[size_t(type)], samples[s].organs[k].s));
          where.push_back({s, k});
        }
    if (pts.empty()) continue;
    std::vector<uint32_t> a = kmeans(pts, P.initial_plantons[size_t(type)], P.kmeans_restarts,
                                     hash64(P.seed, uint64_t(type)));
    uint32_t top = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      labels[where[i].first][where[i].second] = next_label + a[i];
      top = std::max(top, a[i]);
    }
    next_label += top + 1;
  }
  size_t n = canonicalize(labels);
  result.plantons_after_kmeans = n;

  // Hard EM until the labels repeat.
  std::set<std::vector<std::vector<uint32_t>>> seen{labels};
  PlantonModel model;
  for (int it = 0; it < P.max_iterations; ++it) {
    result.iterations = it + 1;
    model = estimate_plantons(samples, labels, n, scales, P.regularization);
    std::vector<std::vector<uint32_t>> next(samples.size());
    for (size_t s = 0; s < samples.size(); ++s) next[s] = relabel_max_product(model, samples[s]);
    // Refine (Algorithm 1 step 5): organs far from their planton's mean start new plantons;
    // outliers close to each other (within e_max) share one.
    std::vector<std::pair<std::vector<double>, uint32_t>> fresh;  // seed z, label
    uint32_t label = uint32_t(n);
    for (size_t s = 0; s < samples.size(); ++s)
      for (size_t k = 0; k < samples[s].organs.size(); ++k) {
        const Organ& o = samples[s].organs[k];
        const Planton& x = model.plantons[next[s][k]];
        std::vector<double> z = to_z(scales[size_t(o.type)], o.s);
        const double dim = double(z.size());
        if (sq_dist(z, x.mean) / dim <= P.e_max) continue;
        uint32_t target = UINT32_MAX;
        for (const auto& [seed_z, l] : fresh)
          if (model.plantons.size() > 0 && seed_z.size() == z.size() && sq_dist(seed_z, z) / dim <= P.e_max) {
            target = l;
            break;
          }
        if (target == UINT32_MAX) {
          target = label++;
          fresh.push_back({z, target});
        }
        next[s][k] = target;
      }
    n = canonicalize(next);
    if (next == labels) {
      result.converged = true;
      break;
    }
    labels = std::move(next);
    if (!seen.insert(labels).second) {  // a cycle of labellings: stop at this one
      result.converged = true;
      model = estimate_plantons(samples, labels, n, scales, P.regularization);
      break;
    }
    model = estimate_plantons(samples, labels, n, scales, P.regularization);
  }
  // Exemplars: every organ of the samples, in its planton.
  for (size_t s = 0; s < samples.size(); ++s)
    for (size_t k = 0; k < samples[s].organs.size(); ++k)
      model.plantons[labels[s][k]].exemplars.push_back(samples[s].organs[k].s);
  result.spectral_radius_before_damping = spectral_radius(offspring_matrix(model), model.N());
  result.spectral_radius = damp_to_subcritical(model);
  result.model = std::move(model);
  result.labels = std::move(labels);
  return result;
}

}  // namespace forest
