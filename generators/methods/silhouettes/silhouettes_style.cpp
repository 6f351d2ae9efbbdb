#include "generators/methods/silhouettes/silhouettes_style.h"

#include <algorithm>
#include <cmath>

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

double signed_angle_deg(glm::dvec2 from, glm::dvec2 to) {
  return std::atan2(from.x * to.y - from.y * to.x, glm::dot(from, to)) * 180.0 / kPi;
}

double normal(Rng& rng) {  // Box-Muller
  double u = std::max(rng.uniform(), 1e-300), v = rng.uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * kPi * v);
}

}  // namespace

BranchingStyle measure_style(const Polyline2& axis, const std::vector<const Branch2D*>& children) {
  BranchingStyle s;
  std::vector<double> ts;
  for (const Branch2D* c : children) {
    if (c->curve.size() < 2) continue;
    ts.push_back(c->t);
    glm::dvec2 start = c->curve[1] - c->curve[0];
    if (glm::length(start) < 1e-12) continue;
    s.baf.add_sample(c->t, std::abs(signed_angle_deg(axis.tangent(c->t), glm::normalize(start))));
  }
  s.children = ts.size();
  if (ts.empty()) return s;
  std::sort(ts.begin(), ts.end());
  s.unbranched = ts.front();
  if (ts.size() >= 2) {
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 1; i < ts.size(); ++i) sum += ts[i] - ts[i - 1];
    s.spacing_mean = sum / double(ts.size() - 1);
    for (size_t i = 1; i < ts.size(); ++i) sum2 += std::pow(ts[i] - ts[i - 1] - s.spacing_mean, 2.0);
    s.spacing_sd = std::sqrt(sum2 / double(ts.size() - 1));
  } else {
    s.spacing_mean = 1.0;  // one child: nothing repeats
  }
  return s;
}

std::vector<double> style_positions(const BranchingStyle& s, Rng& rng, size_t max) {
  std::vector<double> out;
  if (s.children == 0) return out;
  for (double t = s.unbranched; t <= 1.0 && out.size() < max;
       t += std::max(0.02, s.spacing_mean + s.spacing_sd * normal(rng)))
    out.push_back(t);
  return out;
}

int copy_subtree(std::vector<SilhouetteNode>& h, int src, int parent, double t,
                 const std::function<glm::dvec2(glm::dvec2)>& move, size_t max_nodes) {
  std::vector<std::pair<int, int>> todo{{src, parent}};
  int root = -1;
  for (size_t q = 0; q < todo.size() && h.size() < max_nodes; ++q) {
    auto [s, p] = todo[q];
    SilhouetteNode n = h[size_t(s)];
    for (glm::dvec2& v : n.branch.curve) v = move(v);
    for (glm::dvec2& v : n.branch.crown) v = move(v);
    n.parent = p;
    std::vector<int> kids = n.children;
    n.children.clear();
    if (q == 0) n.branch.t = t, n.branch.filled = true, n.branch.sketched = false;
    int id = int(h.size());
    h.push_back(std::move(n));
    h[size_t(p)].children.push_back(id);
    if (q == 0) root = id;
    for (int c : kids) todo.push_back({c, id});
  }
  return root;
}

size_t copy_style(std::vector<SilhouetteNode>& h, int source, Rng& rng, size_t max_nodes) {
  const SilhouetteNode& src = h[size_t(source)];
  Polyline2 src_axis(src.branch.curve);
  std::vector<const Branch2D*> kids;
  for (int c : src.children) kids.push_back(&h[size_t(c)].branch);
  const BranchingStyle style = measure_style(src_axis, kids);
  if (style.children == 0) return 0;
  const std::vector<int> src_children = src.children;
  const int level = src.level;
  const double src_len = std::max(src_axis.length(), 1e-9);
  size_t restyled = 0;
  const size_t n = h.size();
  for (size_t k = 0; k < n; ++k) {
    if (int(k) == source || h[k].level != level || h[k].children.empty()) continue;
    Polyline2 axis(h[k].branch.curve);
    const double scale = axis.length() / src_len;
    const std::vector<int> old_children = h[k].children;
    std::vector<int> fresh;
    for (double t : style_positions(style, rng)) {
      int from = src_children[0];
      for (int c : src_children)
        if (std::abs(h[size_t(c)].branch.t - t) < std::abs(h[size_t(from)].branch.t - t)) from = c;
      // The copy starts at the new place, turned so that its start direction makes the
      // source's BAF(t) with the target's tangent, on the side the source child was.
      const Branch2D& sb = h[size_t(from)].branch;
      glm::dvec2 old_dir = glm::normalize(sb.curve[1] - sb.curve[0]);
      double side = signed_angle_deg(src_axis.tangent(sb.t), old_dir) >= 0.0 ? 1.0 : -1.0;
      glm::dvec2 new_dir = rotate(axis.tangent(t), side * style.baf(t));
      double turn = signed_angle_deg(old_dir, new_dir);
      glm::dvec2 from_base = sb.curve.front(), base = axis.at(t);
      auto move = [&](glm::dvec2 p) { return base + scale * rotate(p - from_base, turn); };
      int id = copy_subtree(h, from, int(k), t, move, max_nodes);
      if (id >= 0) fresh.push_back(id);
    }
    if (fresh.empty()) continue;
    for (int c : old_children) h[size_t(c)].parent = -1;  // detached: no longer drawn
    h[k].children = fresh;
    ++restyled;
  }
  return restyled;
}

}  // namespace forest
