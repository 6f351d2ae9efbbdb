#include "generators/methods/plantons/plantons_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kNegInf = -std::numeric_limits<double>::infinity();
// Variance floors of the likelihood only (the stored model keeps the ML estimates): a child
// count is an integer (rounding variance 1/12), positions and angles are measured.
constexpr double kCountVarFloor = 1.0 / 12.0;
constexpr double kTVarFloor = 0.05 * 0.05;
constexpr double kThetaVarFloor = (3.0 * kPi / 180.0) * (3.0 * kPi / 180.0);
constexpr double kTransitionPrior = 0.01;  // pseudo-count of every transition in the likelihood

double log_normal(double x, double mean, double var) {
  double d = x - mean;
  return -0.5 * (d * d / var + std::log(2.0 * kPi * var));
}

int azimuth_bin(double phi) {
  int b = int(std::floor((phi + kPi) / (2.0 * kPi) * kAzimuthBins));
  return std::clamp(b, 0, kAzimuthBins - 1);
}

struct MeanSd {
  double sum = 0, sum2 = 0, n = 0;
  void add(double x) {
    sum += x;
    sum2 += x * x;
    n += 1;
  }
  double mean() const { return n > 0 ? sum / n : 0.0; }
  double sd() const { return n > 0 ? std::sqrt(std::max(0.0, sum2 / n - mean() * mean())) : 0.0; }
};

// Per planton: Cholesky of the covariance and the normalizing constant of 𝓖.
struct GaussianCache {
  Eigen::LLT<Eigen::MatrixXd> llt;
  double log_norm = 0.0;
};

std::vector<GaussianCache> gaussian_caches(const PlantonModel& model) {
  std::vector<GaussianCache> out(model.N());
  for (size_t i = 0; i < model.N(); ++i) {
    const Planton& x = model.plantons[i];
    const int d = int(x.mean.size());
    Eigen::MatrixXd cov = Eigen::Map<const Eigen::MatrixXd>(x.covariance.data(), d, d);
    out[i].llt.compute(cov);
    double log_det = 0.0;
    Eigen::MatrixXd l = out[i].llt.matrixL();
    for (int k = 0; k < d; ++k) log_det += 2.0 * std::log(l(k, k));
    out[i].log_norm = -0.5 * (log_det + d * std::log(2.0 * kPi));
  }
  return out;
}

}  // namespace

FeatureScales feature_scales(const std::vector<OrganTree>& samples) {
  FeatureScales scales;
  for (int type = 0; type < kOrganTypes; ++type) {
    const int d = organ_param_count(OrganType(type));
    std::vector<MeanSd> acc(static_cast<size_t>(d));
    for (const OrganTree& tree : samples)
      for (const Organ& o : tree.organs)
        if (int(o.type) == type)
          for (int k = 0; k < d; ++k) acc[size_t(k)].add(o.s[size_t(k)]);
    FeatureScale& f = scales[size_t(type)];
    for (int k = 0; k < d; ++k) {
      double sd = acc[size_t(k)].sd();
      f.mean.push_back(acc[size_t(k)].mean());
      f.alpha.push_back(sd > 1e-9 * std::max(1.0, std::abs(acc[size_t(k)].mean())) ? 1.0 / (sd * sd) : 0.0);
    }
  }
  return scales;
}

std::vector<double> to_z(const FeatureScale& scale, const std::vector<double>& s) {
  std::vector<double> z(s.size());
  for (size_t k = 0; k < s.size(); ++k) z[k] = std::sqrt(scale.alpha[k]) * (s[k] - scale.mean[k]);
  return z;
}

std::vector<double> from_z(const FeatureScale& scale, const std::vector<double>& z) {
  std::vector<double> s(z.size());
  for (size_t k = 0; k < z.size(); ++k)
    s[k] = scale.mean[k] + (scale.alpha[k] > 0.0 ? z[k] / std::sqrt(scale.alpha[k]) : 0.0);
  return s;
}

double organ_distance(const Organ& a, const Organ& b, const FeatureScales& scales) {
  if (a.type != b.type) return std::numeric_limits<double>::infinity();
  const FeatureScale& f = scales[size_t(a.type)];
  double d = 0.0;
  for (size_t k = 0; k < a.s.size(); ++k) d += f.alpha[k] * (a.s[k] - b.s[k]) * (a.s[k] - b.s[k]);
  return d;
}

PlantonModel estimate_plantons(const std::vector<OrganTree>& samples,
                               const std::vector<std::vector<uint32_t>>& labels, size_t n,
                               const FeatureScales& scales, double regularization) {
  PlantonModel model;
  model.scales = scales;
  model.regularization = regularization;
  model.plantons.resize(n);
  model.transitions.assign(n * n, Transition{});
  std::vector<std::vector<std::vector<double>>> members(n);
  std::vector<MeanSd> child_counts(n);
  std::vector<MeanSd> t_stats(n * n), theta_stats(n * n);
  std::vector<std::array<double, kAzimuthBins>> az(n * n, std::array<double, kAzimuthBins>{});
  std::vector<size_t> root_votes(n, 0);
  MeanSd root_theta;
  for (size_t si = 0; si < samples.size(); ++si) {
    const OrganTree& tree = samples[si];
    std::vector<uint32_t> kids(tree.organs.size(), 0);
    for (const Organ& o : tree.organs)
      if (o.parent >= 0) ++kids[size_t(o.parent)];
    for (size_t k = 0; k < tree.organs.size(); ++k) {
      const Organ& o = tree.organs[k];
      uint32_t l = labels[si][k];
      model.plantons[l].type = o.type;
      members[l].push_back(to_z(scales[size_t(o.type)], o.s));
      child_counts[l].add(double(kids[k]));
      if (o.parent < 0) {
        ++root_votes[l];
        root_theta.add(o.theta);
        continue;
      }
      size_t e = size_t(labels[si][size_t(o.parent)]) * n + l;
      model.transitions[e].count += 1.0;
      t_stats[e].add(o.t);
      theta_stats[e].add(o.theta);
      az[e][size_t(azimuth_bin(o.phi))] += 1.0;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    Planton& x = model.plantons[i];
    const size_t d = size_t(organ_param_count(x.type));
    const auto& zs = members[i];
    x.organ_count = zs.size();
    x.mean.assign(d, 0.0);
    for (const auto& z : zs)
      for (size_t k = 0; k < d; ++k) x.mean[k] += z[k] / double(zs.size());
    x.covariance.assign(d * d, 0.0);
    for (const auto& z : zs)
      for (size_t a = 0; a < d; ++a)
        for (size_t b = 0; b < d; ++b)
          x.covariance[a * d + b] += (z[a] - x.mean[a]) * (z[b] - x.mean[b]) / double(zs.size());
    for (size_t k = 0; k < d; ++k) x.covariance[k * d + k] += regularization;
    x.child_mean = child_counts[i].mean();
    x.child_sd = child_counts[i].sd();
    double row = 0.0;
    for (size_t j = 0; j < n; ++j) row += model.transitions[i * n + j].count;
    for (size_t j = 0; j < n; ++j) {
      Transition& t = model.a(i, j);
      if (row > 0.0) t.p = t.count / row;
      if (t.count <= 0.0) continue;
      t.t_mean = t_stats[i * n + j].mean();
      t.t_sd = t_stats[i * n + j].sd();
      t.theta_mean = theta_stats[i * n + j].mean();
      t.theta_sd = theta_stats[i * n + j].sd();
      for (int b = 0; b < kAzimuthBins; ++b) t.azimuth[size_t(b)] = az[i * n + j][size_t(b)] / t.count;
    }
  }
  model.root_planton = uint32_t(std::max_element(root_votes.begin(), root_votes.end()) - root_votes.begin());
  model.root_theta_mean = root_theta.mean();
  model.root_theta_sd = root_theta.sd();
  return model;
}

OrganScores unary_scores(const PlantonModel& model, const OrganTree& tree) {
  const size_t n = model.N(), m = tree.organs.size();
  std::vector<GaussianCache> g = gaussian_caches(model);
  std::vector<uint32_t> kids(m, 0);
  for (const Organ& o : tree.organs)
    if (o.parent >= 0) ++kids[size_t(o.parent)];
  OrganScores out;
  out.unary.assign(m * n, kNegInf);
  for (size_t k = 0; k < m; ++k) {
    const Organ& o = tree.organs[k];
    std::vector<double> z = to_z(model.scales[size_t(o.type)], o.s);
    Eigen::Map<const Eigen::VectorXd> zv(z.data(), Eigen::Index(z.size()));
    for (size_t i = 0; i < n; ++i) {
      const Planton& x = model.plantons[i];
      if (x.type != o.type) continue;
      Eigen::VectorXd d = zv - Eigen::Map<const Eigen::VectorXd>(x.mean.data(), Eigen::Index(x.mean.size()));
      double maha = d.dot(g[i].llt.solve(d));
      out.unary[k * n + i] = g[i].log_norm - 0.5 * maha +
                             log_normal(double(kids[k]), x.child_mean, x.child_sd * x.child_sd + kCountVarFloor);
    }
  }
  return out;
}

namespace {
double row_count(const PlantonModel& model, size_t from) {
  double row = 0.0;
  for (size_t j = 0; j < model.N(); ++j) row += model.a(from, j).count;
  return row;
}

double pair_score_with_row(const PlantonModel& model, uint32_t from, uint32_t to, const Organ& child,
                           double row) {
  const size_t n = model.N();
  const Transition& a = model.a(from, to);
  double s = std::log((a.count + kTransitionPrior) / (row + kTransitionPrior * double(n)));
  if (a.count > 0.0) {
    s += log_normal(child.t, a.t_mean, a.t_sd * a.t_sd + kTVarFloor);
    s += log_normal(child.theta, a.theta_mean, a.theta_sd * a.theta_sd + kThetaVarFloor);
    double h = (a.azimuth[size_t(azimuth_bin(child.phi))] * a.count + 1.0) / (a.count + kAzimuthBins);
    s += std::log(h * kAzimuthBins / (2.0 * kPi));
  } else {
    s += -std::log(kPi) - std::log(2.0 * kPi);  // T, θ, φ uniform
  }
  return s;
}
}  // namespace

double pair_score(const PlantonModel& model, uint32_t from, uint32_t to, const Organ& child) {
  return pair_score_with_row(model, from, to, child, row_count(model, from));
}

double labelling_log_likelihood(const PlantonModel& model, const OrganTree& tree,
                                const std::vector<uint32_t>& labels) {
  OrganScores u = unary_scores(model, tree);
  double total = 0.0;
  for (size_t k = 0; k < tree.organs.size(); ++k) {
    total += u.unary[k * model.N() + labels[k]];
    const Organ& o = tree.organs[k];
    if (o.parent >= 0) total += pair_score(model, labels[size_t(o.parent)], labels[k], o);
  }
  return total;
}

std::vector<uint32_t> relabel_max_product(const PlantonModel& model, const OrganTree& tree) {
  const size_t n = model.N(), m = tree.organs.size();
  OrganScores u = unary_scores(model, tree);
  // best[k * n + l]: best log-likelihood of the subtree of organ k given that k has label l
  // (its unary plus its children's messages). Children have larger indices, so one pass from
  // the last organ to the first sees every child before its parent.
  std::vector<double> best = u.unary;
  std::vector<uint32_t> choice(m * n, 0);  // argmax label of k given its parent's label
  std::vector<double> rows(n);
  for (size_t i = 0; i < n; ++i) rows[i] = row_count(model, i);
  for (size_t k = m; k-- > 1;) {
    const Organ& o = tree.organs[k];
    const size_t p = size_t(o.parent);
    for (size_t lp = 0; lp < n; ++lp) {
      if (model.plantons[lp].type != tree.organs[p].type) continue;
      double top = kNegInf;
      uint32_t arg = 0;
      for (size_t l = 0; l < n; ++l) {
        if (best[k * n + l] == kNegInf) continue;
        double v = best[k * n + l] + pair_score_with_row(model, uint32_t(lp), uint32_t(l), o, rows[lp]);
        if (v > top) {
          top = v;
          arg = uint32_t(l);
        }
      }
      best[p * n + lp] += top;
      choice[k * n + lp] = arg;
    }
  }
  std::vector<uint32_t> labels(m, 0);
  labels[0] = uint32_t(std::max_element(best.begin(), best.begin() + long(n)) - best.begin());
  for (size_t k = 1; k < m; ++k) labels[k] = choice[k * n + labels[size_t(tree.organs[k].parent)]];
  return labels;
}

double expected_children(double mean, double sd) {
  if (!(sd > 1e-9)) return std::max(0.0, std::floor(mean + 0.5));
  auto cdf = [&](double x) { return 0.5 * std::erfc(-(x - mean) / (sd * std::sqrt(2.0))); };
  double e = 0.0;
  const double hi = std::max(1.0, mean + 12.0 * sd + 2.0);
  for (double k = 1.0; k <= hi; k += 1.0) e += k * (cdf(k + 0.5) - cdf(k - 0.5));
  return e;
}

std::vector<double> offspring_matrix(const PlantonModel& model) {
  const size_t n = model.N();
  std::vector<double> m(n * n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (model.plantons[i].type == OrganType::Leaf) continue;
    double en = expected_children(model.plantons[i].child_mean, model.plantons[i].child_sd);
    for (size_t j = 0; j < n; ++j) m[i * n + j] = en * model.a(i, j).p;
  }
  return m;
}

double spectral_radius(const std::vector<double>& matrix, size_t n) {
  if (n == 0) return 0.0;
  Eigen::MatrixXd a(n, n);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) a(Eigen::Index(i), Eigen::Index(j)) = matrix[i * n + j];
  Eigen::EigenSolver<Eigen::MatrixXd> es(a, false);
  double r = 0.0;
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) r = std::max(r, std::abs(es.eigenvalues()[i]));
  return r;
}

std::vector<double> expected_organ_counts(const PlantonModel& model) {
  const size_t n = model.N();
  std::vector<double> m = offspring_matrix(model);
  if (spectral_radius(m, n) >= 1.0) return {};
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(Eigen::Index(n), Eigen::Index(n));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) a(Eigen::Index(i), Eigen::Index(j)) -= m[i * n + j];
  Eigen::VectorXd x = a.partialPivLu().solve(Eigen::VectorXd::Ones(Eigen::Index(n)));
  return std::vector<double>(x.data(), x.data() + n);
}

double damp_to_subcritical(PlantonModel& model, double target) {
  auto radius = [&](const PlantonModel& m) { return spectral_radius(offspring_matrix(m), m.N()); };
  double r = radius(model);
  if (r <= target) return r;
  std::vector<double> means;
  for (const Planton& x : model.plantons) means.push_back(x.child_mean);
  auto apply = [&](double g) {
    for (size_t i = 0; i < model.N(); ++i) model.plantons[i].child_mean = means[i] * g;
  };
  double lo = 0.0, hi = 1.0;  // radius(lo) <= target < radius(hi)
  for (int it = 0; it < 40; ++it) {
    double mid = 0.5 * (lo + hi);
    apply(mid);
    (radius(model) <= target ? lo : hi) = mid;
  }
  apply(lo);
  model.damping *= lo;
  return radius(model);
}

}  // namespace forest
