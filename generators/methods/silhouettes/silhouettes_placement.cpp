#include "generators/methods/silhouettes/silhouettes_placement.h"

#include <algorithm>
#include <cmath>

#include "generators/core/rng.h"

namespace forest {

bool phyllotaxis_preset(const std::string& name, BranchPhyllotaxis& out) {
  if (name == "none") out = {0, 0.0};
  else if (name == "spiral") out = {1, 144.0};
  else if (name == "decussate") out = {2, 90.0};
  else if (name == "whorl3") out = {3, 60.0};
  else return false;
  return true;
}

double insertion_distance(const InsertionPoint& a, const InsertionPoint& b, double length) {
  double du = length > 0 ? (a.u - b.u) / length : 0.0;
  double dt = std::fmod(std::abs(a.theta - b.theta), 360.0);
  dt = std::min(dt, 360.0 - dt) / 360.0;
  return du * du + dt * dt;
}

double pattern_distance(const InsertionPoint& a, const InsertionPoint& b, double length, int count,
                        const BranchPhyllotaxis& p) {
  if (p.whorl <= 0 || count <= 0 || length <= 0) return 0.0;
  const InsertionPoint& lo = a.u <= b.u ? a : b;
  const InsertionPoint& hi = a.u <= b.u ? b : a;
  double gamma = 360.0 / p.whorl;
  double l = length * p.whorl / count;
  double d_node = std::floor((hi.u - lo.u) / l);
  double d_ang = std::fmod(hi.theta - lo.theta - d_node * p.phi_deg, gamma);
  if (d_ang < 0) d_ang += gamma;
  return std::clamp(std::min(d_ang, gamma - d_ang) / gamma, 0.0, 0.5);
}

namespace {
double pair_cost(const InsertionPoint& a, const InsertionPoint& b, double length, int count, const BranchPhyllotaxis& p,
                 const GibbsParams& g) {
  double f = 1.0 / (1.0 + g.alpha * insertion_distance(a, b, length));
  if (p.whorl <= 0) return f;
  return g.w_close * f + g.w_pattern * pattern_distance(a, b, length, count, p);
}
}  // namespace

double gibbs_energy(const std::vector<InsertionPoint>& pts, double length, const BranchPhyllotaxis& p,
                    const GibbsParams& g) {
  double e = 0.0;
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t j = 0; j < pts.size(); ++j)
      if (i != j) e += pair_cost(pts[i], pts[j], length, int(pts.size()), p, g);
  return e;
}

GibbsResult place_insertion_points(std::vector<InsertionPoint>& pts, double length, const BranchPhyllotaxis& p,
                                   const GibbsParams& g, uint64_t seed) {
  GibbsResult r;
  const int n = int(pts.size());
  double energy = gibbs_energy(pts, length, p, g);
  r.energy.push_back(energy);
  if (n < 2) return r;
  Rng rng(seed, /*stream=*/31);
  // Energy terms of point i (both orders of every pair it is in).
  auto terms = [&](int i) {
    double e = 0.0;
    for (int j = 0; j < n; ++j)
      if (j != i) e += 2.0 * pair_cost(pts[size_t(i)], pts[size_t(j)], length, n, p, g);
    return e;
  };
  for (int it = 0; it < std::min(g.max_iterations, 3000); ++it) {
    int i = int(rng.next_u32() % uint32_t(n));
    InsertionPoint& q = pts[size_t(i)];
    InsertionPoint old = q;
    double before = terms(i);
    q.u = q.u_min + (q.u_max - q.u_min) * rng.uniform();
    double theta = q.theta_min + (q.theta_max - q.theta_min) * rng.uniform();
    q.theta = std::fmod(std::fmod(theta, 360.0) + 360.0, 360.0);
    if (q.theta_max - q.theta_min < 360.0) q.theta = theta;  // bounded domains keep their range
    double after = terms(i);
    if (after < before) energy += after - before;
    else q = old;
    r.energy.push_back(energy);
    r.iterations = it + 1;
  }
  return r;
}

}  // namespace forest
