#include "generators/methods/plantons/plantons_synth.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

#include <Eigen/Dense>

#include "generators/core/rng.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

double normal(Rng& rng) {  // Box–Muller, one value per call (deterministic)
  double u1 = std::max(rng.uniform(), 1e-300), u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

struct PlantonSampler {
  Eigen::MatrixXd chol;                       // L of the covariance
  std::vector<std::vector<double>> exemplar_z;
};

}  // namespace

SynthesizedTree synthesize_plantons(const PlantonModel& model, const SynthesisParams& P, uint64_t seed) {
  const size_t n = model.N();
  SynthesizedTree out;
  if (n == 0) return out;
  std::vector<PlantonSampler> samplers(n);
  for (size_t i = 0; i < n; ++i) {
    const Planton& x = model.plantons[i];
    const int d = int(x.mean.size());
    Eigen::MatrixXd cov = Eigen::Map<const Eigen::MatrixXd>(x.covariance.data(), d, d);
    samplers[i].chol = cov.llt().matrixL();
    for (const auto& e : x.exemplars) samplers[i].exemplar_z.push_back(to_z(model.scales[size_t(x.type)], e));
  }
  std::vector<double> row_sum(n, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) row_sum[i] += model.a(i, j).p;

  Rng rng(seed, 41);
  // Organ parameters of planton i: a sample of 𝓖, then the nearest exemplar scaled to it.
  auto organ_params = [&](uint32_t i) {
    const Planton& x = model.plantons[i];
    const FeatureScale& scale = model.scales[size_t(x.type)];
    const size_t d = x.mean.size();
    Eigen::VectorXd e(Eigen::Index(d), 1);
    for (size_t k = 0; k < d; ++k) e[Eigen::Index(k)] = normal(rng);
    Eigen::VectorXd zs = samplers[i].chol * e;
    std::vector<double> z(d);
    for (size_t k = 0; k < d; ++k) z[k] = x.mean[k] + zs[Eigen::Index(k)];
    std::vector<double> sampled = from_z(scale, z);
    if (samplers[i].exemplar_z.empty()) return sampled;  // a hand-made model (ground truth)
    size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < samplers[i].exemplar_z.size(); ++k) {
      double dd = 0.0;
      for (size_t c = 0; c < d; ++c) dd += (samplers[i].exemplar_z[k][c] - z[c]) * (samplers[i].exemplar_z[k][c] - z[c]);
      if (dd < best_d) {
        best_d = dd;
        best = k;
      }
    }
    std::vector<double> s = x.exemplars[best];
    double f = s[0] > 1e-9 ? std::clamp(sampled[0] / s[0], 0.5, 2.0) : 1.0;
    s[0] *= f;
    if (x.type == OrganType::Stem) {
      s[1] *= f;
      s[2] *= f;
    }
    return s;
  };
  auto clean = [](std::vector<double>& s, OrganType type) {
    s[0] = std::max(s[0], 1e-3);
    if (type == OrganType::Stem) {
      s[1] = std::max(s[1], 1e-4);
      s[2] = std::clamp(s[2], 1e-4, s[1]);
    }
  };

  std::vector<uint32_t> depth;
  std::deque<uint32_t> queue;
  {
    Organ root;
    root.type = model.plantons[model.root_planton].type;
    root.s = organ_params(model.root_planton);
    clean(root.s, root.type);
    root.theta = std::clamp(model.root_theta_mean + model.root_theta_sd * normal(rng), 0.0, kPi);
    root.phi = (2.0 * rng.uniform() - 1.0) * kPi;
    root.direction = glm::vec3(direction_from_angles(glm::dvec3(0, 1, 0), root.theta, root.phi));
    out.tree.organs.push_back(root);
    out.plantons.push_back(model.root_planton);
    depth.push_back(0);
    queue.push_back(0);
  }
  while (!queue.empty()) {
    const uint32_t k = queue.front();
    queue.pop_front();
    const uint32_t i = out.plantons[k];
    const Planton& x = model.plantons[i];
    if (x.type != OrganType::Stem || !(row_sum[i] > 0.0)) continue;
    double draw = std::floor(x.child_mean + x.child_sd * normal(rng) + 0.5);
    int children = int(std::clamp(draw, 0.0, 1e6));
    if (children > 0 && depth[k] >= P.max_depth) {
      out.capped = true;
      continue;
    }
    const std::array<glm::dvec3, 4> curve = stem_control_points(out.tree.organs[k]);
    // Planton and position of every child first: the divergences φ chain the siblings in
    // order of t (as learned).
    struct Child {
      uint32_t planton;
      double t;
    };
    std::vector<Child> kids;
    for (int c = 0; c < children; ++c) {
      if (out.tree.organs.size() + kids.size() >= P.max_organs) {
        out.capped = true;
        break;
      }
      double pick = rng.uniform() * row_sum[i];
      uint32_t j = 0;
      for (size_t jj = 0; jj < n; ++jj) {
        pick -= model.a(i, jj).p;
        j = uint32_t(jj);
        if (pick < 0.0) break;
      }
      const Transition& a = model.a(i, j);
      kids.push_back({j, std::clamp(a.t_mean + a.t_sd * normal(rng), 0.0, 1.0)});
    }
    std::stable_sort(kids.begin(), kids.end(), [](const Child& a, const Child& b) { return a.t < b.t; });
    double azimuth = 0.0;  // absolute, from the upper side of the parent's tangent
    for (const Child& kid : kids) {
      const uint32_t j = kid.planton;
      const Transition& a = model.a(i, j);
      Organ o;
      o.type = model.plantons[j].type;
      o.parent = int32_t(k);
      o.t = kid.t;
      o.theta = std::clamp(a.theta_mean + a.theta_sd * normal(rng), 0.0, kPi);
      double bin = rng.uniform(), acc = 0.0;
      int b = 0;
      for (; b < kAzimuthBins - 1; ++b) {
        acc += a.azimuth[size_t(b)];
        if (bin < acc) break;
      }
      o.phi = -kPi + (double(b) + rng.uniform()) * (2.0 * kPi / kAzimuthBins);
      azimuth += o.phi;
      o.base = glm::vec3(bezier_point(curve, o.t));
      o.direction = glm::vec3(direction_from_angles(bezier_tangent(curve, o.t), o.theta, azimuth));
      o.s = organ_params(j);
      clean(o.s, o.type);
      if (o.type == OrganType::Stem) {  // no child thicker than its parent where it starts
        const std::vector<double>& ps = out.tree.organs[k].s;
        double r_at = ps[1] + (ps[2] - ps[1]) * o.t;
        o.s[1] = std::min(o.s[1], r_at);
        o.s[2] = std::min(o.s[2], o.s[1]);
      }
      out.tree.organs.push_back(std::move(o));
      out.plantons.push_back(j);
      depth.push_back(depth[k] + 1);
      queue.push_back(uint32_t(out.tree.organs.size() - 1));
    }
  }
  return out;
}

}  // namespace forest
