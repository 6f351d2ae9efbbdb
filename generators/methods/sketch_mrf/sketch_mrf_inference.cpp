#include "generators/methods/sketch_mrf/sketch_mrf_inference.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numeric>

#include "generators/core/input_error.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

double log_normal(double x, double mu, double sd) {
  double u = (x - mu) / sd;
  return -0.5 * u * u - std::log(sd);
}

glm::dvec3 pos(const SketchTree& t, const std::vector<double>& z, int i) {
  return {t.xy[size_t(i)].x, t.xy[size_t(i)].y, z[size_t(i)]};
}

glm::dvec3 vec(const SketchTree& t, const std::vector<double>& z, int i) {
  return pos(t, z, i) - pos(t, z, t.parent[size_t(i)]);
}

// Nodes in breadth-first order from the root (parents before children).
std::vector<int> bfs_order(const SketchTree& t) {
  std::vector<int> order{0};
  for (size_t k = 0; k < order.size(); ++k)
    for (int c : t.children[size_t(order[k])]) order.push_back(c);
  return order;
}

bool has_parent_segment(const SketchTree& t, int i) { return i > 0 && t.parent[size_t(i)] > 0; }

using Frame = SegmentFrame;

}  // namespace

// Frame of segment c from its parent's frame by the minimal rotation taking t_p to t_c.
Frame transport_frame(const Frame& p, glm::dvec3 v) {
  Frame f;
  double len = glm::length(v);
  f.t = len > 0 ? v / len : p.t;
  glm::dvec3 axis = glm::cross(p.t, f.t);
  double sin_a = glm::length(axis), cos_a = glm::dot(p.t, f.t);
  glm::dvec3 n = p.n;
  if (sin_a > 1e-12) {
    glm::dvec3 k = axis / sin_a;
    n = n * cos_a + glm::cross(k, n) * sin_a + k * glm::dot(k, n) * (1.0 - cos_a);
  }
  n -= glm::dot(n, f.t) * f.t;
  if (glm::length(n) < 1e-9) n = std::abs(f.t.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  f.n = glm::normalize(n - glm::dot(n, f.t) * f.t);
  f.b = glm::cross(f.t, f.n);
  return f;
}

namespace {

Frame root_frame(glm::dvec3 v) { return transport_frame(Frame{}, v); }

std::vector<Frame> frames_of(const SketchTree& t, const std::vector<double>& z) {
  std::vector<Frame> f(t.xy.size());
  for (int i : bfs_order(t)) {
    if (i == 0) continue;
    int p = t.parent[size_t(i)];
    f[size_t(i)] = p == 0 ? root_frame(vec(t, z, i)) : transport_frame(f[size_t(p)], vec(t, z, i));
  }
  return f;
}

SegmentAngles angles_of(glm::dvec3 vc, glm::dvec3 vp, const Frame& fp) {
  SegmentAngles a;
  double lc = glm::length(vc), lp = glm::length(vp);
  a.s = lp > 0 ? lc / lp : 1.0;
  a.angle = lc > 0 && lp > 0 ? std::acos(std::clamp(glm::dot(vc, vp) / (lc * lp), -1.0, 1.0)) : 0.0;
  a.gamma = std::atan2(glm::dot(vc, fp.b), glm::dot(vc, fp.n));
  return a;
}

double factor(const SegmentAngles& a, int label, int K, const Omega& o) {
  double f = log_normal(a.s, o.mu_s, o.sd_s);
  f += label == 0 ? log_normal(a.angle, o.mu_a, o.sd_a) : log_normal(a.angle, o.mu_b, o.sd_b);
  f += log_normal(wrap(a.gamma - o.mu_g - label_gamma_offset(label, K)), 0.0, o.sd_g);
  return f;
}

double factor_sa(const SketchTree& t, const std::vector<double>& z, int c, int label, const Omega& o) {
  glm::dvec3 vc = vec(t, z, c), vp = vec(t, z, t.parent[size_t(c)]);
  SegmentAngles a = angles_of(vc, vp, Frame{});
  double f = log_normal(a.s, o.mu_s, o.sd_s);
  return f + (label == 0 ? log_normal(a.angle, o.mu_a, o.sd_a) : log_normal(a.angle, o.mu_b, o.sd_b));
}

// The 25^3 density grid of eq. 4.22 over the drawing (a cube of the drawing's extent).
struct DensityGrid {
  glm::dvec3 lo{0.0};
  double h = 1.0;
  glm::dvec3 center(glm::dvec3 p) const {
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) c[k] = lo[k] + (std::clamp(std::floor((p[k] - lo[k]) / h), 0.0, 24.0) + 0.5) * h;
    return c;
  }
  double g(glm::dvec3 p, glm::dvec3 c) const {
    glm::dvec3 d = (p - c) / h;
    return 1.0 / (1.0 + glm::dot(d, d));
  }
};

DensityGrid grid_of(const SketchTree& t) {
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2 p : t.xy) lo = glm::min(lo, p), hi = glm::max(hi, p);
  double e = std::max({hi.x - lo.x, hi.y - lo.y, 1e-6});
  DensityGrid g;
  g.lo = glm::dvec3(0.5 * (lo.x + hi.x) - 0.5 * e, 0.5 * (lo.y + hi.y) - 0.5 * e, -0.5 * e);
  g.h = e / 25.0;
  return g;
}

bool adjacent(const SketchTree& t, int i, int j) {
  return i == j || t.parent[size_t(i)] == j || t.parent[size_t(j)] == i;
}

// Density terms that involve node i: its own field and its contribution to the others'.
double density_terms(const SketchTree& t, const std::vector<double>& z, const DensityGrid& g, int i) {
  glm::dvec3 pi = pos(t, z, i), ci = g.center(pi);
  double sum = 0.0;
  for (size_t j = 0; j < t.xy.size(); ++j) {
    if (adjacent(t, i, int(j))) continue;
    glm::dvec3 pj = pos(t, z, int(j));
    sum += g.g(pi, g.center(pj)) + g.g(pj, ci);
  }
  return sum;
}

}  // namespace

std::vector<SegmentFrame> segment_frames(const SketchTree& tree, const std::vector<double>& z) {
  return frames_of(tree, z);
}

double label_gamma_offset(int label, int K) {
  if (label <= 0 || K < 2) return 0.0;
  return kPi + 2.0 * kPi * double(label - 1) / double(K - 1);
}

std::vector<std::vector<int>> label_hypotheses(int K) {
  if (K < 0 || K > kMaxSketchChildren) throw InputError("label_hypotheses: K out of range");
  std::vector<int> perm(static_cast<size_t>(K));
  std::iota(perm.begin(), perm.end(), 0);
  std::vector<std::vector<int>> out;
  do out.push_back(perm);
  while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

SketchTree sketch_tree_from_drawing(const Drawing& drawing) {
  std::vector<int> stroke_parent = stroke_parents(drawing);
  SketchTree t;
  int root_stroke = -1;
  std::vector<std::vector<int>> stroke_children(drawing.strokes.size());
  glm::dvec2 lo(1e300), hi(-1e300);
  for (size_t i = 0; i < drawing.strokes.size(); ++i) {
    const Stroke& s = drawing.strokes[i];
    if (s.role == "crown") {
      t.crown.insert(t.crown.end(), s.points.begin(), s.points.end());
      continue;
    }
    if (s.role != "branch") stroke_error(drawing, i, "role", "sketch-mrf reads roles \"branch\" and \"crown\", not \"" + s.role + "\"");
    for (glm::dvec2 p : s.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
    int p = stroke_parent[i];
    if (p < 0) {
      if (root_stroke >= 0) stroke_error(drawing, i, "parent", "only one branch stroke (the trunk) may lack a parent");
      root_stroke = int(i);
    } else {
      if (drawing.strokes[size_t(p)].role != "branch") stroke_error(drawing, i, "parent", "the parent must be a branch stroke");
      stroke_children[size_t(p)].push_back(int(i));
    }
  }
  if (root_stroke < 0) throw InputError(drawing.file, 0, "strokes", "no branch stroke (a trunk stroke without parent is needed)");
  t.height = std::max({hi.x - lo.x, hi.y - lo.y, 1e-6});
  bool with_depth = true;
  for (const Stroke& s : drawing.strokes)
    if (s.role == "branch" && s.depth.empty()) with_depth = false;

  std::vector<std::vector<int>> nodes_of(drawing.strokes.size());
  const double dup = 1e-9 * t.height;
  auto add_node = [&](glm::dvec2 xy, int parent, double z) {
    t.xy.push_back(xy);
    t.parent.push_back(parent);
    t.true_z.push_back(z);
    return int(t.xy.size()) - 1;
  };
  std::vector<int> queue{root_stroke};
  for (size_t q = 0; q < queue.size(); ++q) {
    size_t si = size_t(queue[q]);
    const Stroke& s = drawing.strokes[si];
    std::vector<int>& list = nodes_of[si];
    size_t first = 1;
    if (int(si) == root_stroke) {
      list.push_back(add_node(s.points[0], -1, with_depth ? s.depth[0] : 0.0));
    } else {
      // Attach to the nearest point of the parent stroke.
      std::vector<int>& pl = nodes_of[size_t(stroke_parent[si])];
      double best = 1e300, best_a = 0;
      size_t best_k = 0;
      for (size_t k = 0; k + 1 < pl.size(); ++k) {
        glm::dvec2 a = t.xy[size_t(pl[k])], b = t.xy[size_t(pl[k + 1])];
        glm::dvec2 ab = b - a;
        double u = glm::dot(ab, ab) > 0 ? std::clamp(glm::dot(s.points[0] - a, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
        double dist = glm::length(a + u * ab - s.points[0]);
        if (dist < best) best = dist, best_a = u, best_k = k;
      }
      if (best > 0.1 * t.height)
        stroke_error(drawing, si, "points", "does not start on its parent stroke (" + std::to_string(best) + " m away)");
      int attach;
      if (best_a < 1e-6) attach = pl[best_k];
      else if (best_a > 1.0 - 1e-6) attach = pl[best_k + 1];
      else {
        int a = pl[best_k], b = pl[best_k + 1];
        double z = (1 - best_a) * t.true_z[size_t(a)] + best_a * t.true_z[size_t(b)];
        attach = add_node(glm::mix(t.xy[size_t(a)], t.xy[size_t(b)], best_a), a, z);
        t.parent[size_t(b)] = attach;
        pl.insert(pl.begin() + long(best_k) + 1, attach);
      }
      list.push_back(attach);
    }
    for (size_t k = first; k < s.points.size(); ++k) {
      if (glm::length(s.points[k] - t.xy[size_t(list.back())]) <= dup) continue;
      list.push_back(add_node(s.points[k], list.back(), with_depth ? s.depth[k] : 0.0));
    }
    if (list.size() < 2) stroke_error(drawing, si, "points", "the stroke has zero length");
    for (int c : stroke_children[si]) queue.push_back(c);
  }
  if (!with_depth) t.true_z.clear();
  t.children.assign(t.xy.size(), {});
  for (size_t i = 1; i < t.xy.size(); ++i) t.children[size_t(t.parent[i])].push_back(int(i));
  for (size_t i = 0; i < t.xy.size(); ++i)
    if (t.children[i].size() > size_t(kMaxSketchChildren))
      throw InputError(drawing.file, 0, "strokes", "more than 7 segments leave the point (" +
                       std::to_string(t.xy[i].x) + ", " + std::to_string(t.xy[i].y) + ")");
  return t;
}

std::vector<SegmentAngles> segment_angles(const SketchTree& t, const std::vector<double>& z) {
  std::vector<Frame> f = frames_of(t, z);
  std::vector<SegmentAngles> out(t.xy.size());
  for (size_t c = 1; c < t.xy.size(); ++c) {
    if (!has_parent_segment(t, int(c))) continue;
    int p = t.parent[c];
    out[c] = angles_of(vec(t, z, int(c)), vec(t, z, p), f[size_t(p)]);
  }
  return out;
}

std::vector<int> natural_labels(const SketchTree& t, const std::vector<double>& z) {
  std::vector<SegmentAngles> a = segment_angles(t, z);
  std::vector<int> label(t.xy.size(), -1);
  for (size_t p = 1; p < t.xy.size(); ++p) {
    std::vector<int> c = t.children[p];
    if (c.empty()) continue;
    size_t apical = 0;
    for (size_t k = 1; k < c.size(); ++k)
      if (a[size_t(c[k])].angle < a[size_t(c[apical])].angle) apical = k;
    int apical_node = c[apical];
    label[size_t(apical_node)] = 0;
    c.erase(c.begin() + long(apical));
    double g0 = a[size_t(apical_node)].gamma;
    std::sort(c.begin(), c.end(), [&](int x, int y) {
      double gx = wrap(a[size_t(x)].gamma - g0 - kPi) + kPi, gy = wrap(a[size_t(y)].gamma - g0 - kPi) + kPi;
      return gx != gy ? gx < gy : x < y;
    });
    for (size_t k = 0; k < c.size(); ++k) label[size_t(c[k])] = int(k) + 1;
  }
  return label;
}

double log_posterior(const SketchTree& t, const SketchDepths& d, const Omega& o) {
  std::vector<SegmentAngles> a = segment_angles(t, d.z);
  double sum = 0.0;
  for (size_t c = 1; c < t.xy.size(); ++c) {
    if (!has_parent_segment(t, int(c))) continue;
    int K = int(t.children[size_t(t.parent[c])].size());
    sum += factor(a[c], std::max(d.label[c], 0), K, o);
  }
  return sum;
}

double log_p_icm(const SketchTree& t, const SketchDepths& d, const Omega& o, double k_e) {
  DensityGrid g = grid_of(t);
  double sum = 0.0;
  for (size_t c = 1; c < t.xy.size(); ++c)
    if (has_parent_segment(t, int(c))) sum += factor_sa(t, d.z, int(c), std::max(d.label[c], 0), o);
  double density = 0.0;
  for (size_t i = 0; i < t.xy.size(); ++i) {
    glm::dvec3 pi = pos(t, d.z, int(i));
    for (size_t j = 0; j < t.xy.size(); ++j)
      if (!adjacent(t, int(i), int(j))) density += g.g(pi, g.center(pos(t, d.z, int(j))));
  }
  return sum - k_e * density / double(t.xy.size());
}

SketchDepths infer_bottom_up(const SketchTree& t, const Omega& o) {
  SketchDepths d;
  d.z.assign(t.xy.size(), 0.0);
  d.label.assign(t.xy.size(), -1);
  std::vector<Frame> f(t.xy.size());
  for (int p : bfs_order(t)) {
    if (p == 0) continue;
    int pp = t.parent[size_t(p)];
    f[size_t(p)] = pp == 0 ? root_frame(vec(t, d.z, p)) : transport_frame(f[size_t(pp)], vec(t, d.z, p));
    const std::vector<int>& c = t.children[size_t(p)];
    const int K = int(c.size());
    if (K == 0) continue;
    glm::dvec3 vp = vec(t, d.z, p);
    // best[k][l]: the best log factor of child k under label l, and its depth offset.
    std::vector<std::vector<double>> best(static_cast<size_t>(K), std::vector<double>(static_cast<size_t>(K)));
    std::vector<std::vector<double>> best_dz = best;
    for (int k = 0; k < K; ++k) {
      glm::dvec2 dxy = t.xy[size_t(c[size_t(k)])] - t.xy[size_t(p)];
      double range = 3.0 * std::max(glm::length(dxy), glm::length(vp)) + 1e-9;
      for (int l = 0; l < K; ++l) {
        auto value = [&](double dz) { return factor(angles_of({dxy.x, dxy.y, dz}, vp, f[size_t(p)]), l, K, o); };
        const int n = 240;
        double step = 2.0 * range / n, bz = -range, bv = value(-range);
        for (int s = 1; s <= n; ++s) {
          double zz = -range + step * s, v = value(zz);
          if (v > bv) bv = v, bz = zz;
        }
        // Golden-section refinement around the best grid sample.
        double a = bz - step, b = bz + step;
        const double r = 0.6180339887498949;
        for (int it = 0; it < 40; ++it) {
          double x1 = b - r * (b - a), x2 = a + r * (b - a);
          if (value(x1) >= value(x2)) b = x2; else a = x1;
        }
        double zm = 0.5 * (a + b), vm = value(zm);
        if (vm > bv) bv = vm, bz = zm;
        best[size_t(k)][size_t(l)] = bv;
        best_dz[size_t(k)][size_t(l)] = bz;
      }
    }
    double top = -1e300;
    std::vector<int> chosen;
    for (const std::vector<int>& h : label_hypotheses(K)) {
      double sum = 0.0;
      for (int k = 0; k < K; ++k) sum += best[size_t(k)][size_t(h[size_t(k)])];
      if (sum > top) top = sum, chosen = h;
    }
    for (int k = 0; k < K; ++k) {
      int ci = c[size_t(k)];
      d.label[size_t(ci)] = chosen[size_t(k)];
      d.z[size_t(ci)] = d.z[size_t(p)] + best_dz[size_t(k)][size_t(chosen[size_t(k)])];
    }
  }
  return d;
}

void separate_crossings(const SketchTree& t, SketchDepths& d) {
  const double gap = 0.02 * t.height;
  auto subtree = [&](int root) {
    std::vector<int> s{root};
    for (size_t k = 0; k < s.size(); ++k)
      for (int c : t.children[size_t(s[k])]) s.push_back(c);
    return s;
  };
  for (size_t i = 1; i < t.xy.size(); ++i) {
    for (size_t j = i + 1; j < t.xy.size(); ++j) {
      int pi = t.parent[i], pj = t.parent[j];
      if (pi == pj || pi == int(j) || pj == int(i)) continue;
      glm::dvec2 a0 = t.xy[size_t(pi)], a1 = t.xy[i], b0 = t.xy[size_t(pj)], b1 = t.xy[j];
      glm::dvec2 r = a1 - a0, s = b1 - b0;
      double den = r.x * s.y - r.y * s.x;
      if (std::abs(den) < 1e-12) continue;
      glm::dvec2 w = b0 - a0;
      double u = (w.x * s.y - w.y * s.x) / den, v = (w.x * r.y - w.y * r.x) / den;
      if (u <= 0 || u >= 1 || v <= 0 || v >= 1) continue;
      double za = d.z[size_t(pi)] + u * (d.z[i] - d.z[size_t(pi)]);
      double zb = d.z[size_t(pj)] + v * (d.z[j] - d.z[size_t(pj)]);
      if (std::abs(za - zb) >= gap || !has_parent_segment(t, int(j))) continue;
      double shift = (zb >= za ? 1.0 : -1.0) * (gap - std::abs(za - zb)) / std::max(v, 0.25);
      for (int n : subtree(int(j))) d.z[size_t(n)] += shift;
    }
  }
}

void refine_icm(const SketchTree& t, SketchDepths& d, const Omega& o, const InferenceParams& params,
                std::vector<double>* log_p) {
  DensityGrid g = grid_of(t);
  std::vector<int> order = bfs_order(t);
  auto local = [&](int i) {
    double sum = 0.0;
    auto add = [&](int c) {
      if (has_parent_segment(t, c)) sum += factor_sa(t, d.z, c, std::max(d.label[size_t(c)], 0), o);
    };
    add(i);
    for (int c : t.children[size_t(i)]) {
      add(c);
      for (int gc : t.children[size_t(c)]) add(gc);
    }
    return sum - params.k_e * density_terms(t, d.z, g, i) / double(t.xy.size());
  };
  const double H = t.height, eps = 1e-4 * H;
  double last = -1e300;
  for (int sweep = 0; sweep < params.max_icm_sweeps; ++sweep) {
    double moved = 0.0;
    for (int i : order) {
      if (i == 0 || t.parent[size_t(i)] == 0) continue;  // root and root segments stay at z = 0
      double z0 = d.z[size_t(i)], f0 = local(i);
      d.z[size_t(i)] = z0 + eps;
      double fp = local(i);
      d.z[size_t(i)] = z0 - eps;
      double fm = local(i);
      d.z[size_t(i)] = z0;
      double grad = (fp - fm) / (2 * eps);
      if (!std::isfinite(grad) || grad == 0.0) continue;
      double step = (grad > 0 ? 1.0 : -1.0) * std::min(0.05 * H, std::abs(grad) * 0.01 * H * H);
      for (int k = 0; k < 12; ++k, step *= 0.5) {
        d.z[size_t(i)] = z0 + step;
        if (local(i) > f0) break;
        d.z[size_t(i)] = z0;
      }
      moved += std::abs(d.z[size_t(i)] - z0);
    }
    double value = log_p_icm(t, d, o, params.k_e);
    if (log_p) log_p->push_back(value);
    // Converged: the depths barely move or log p barely rises any more.
    if (moved < params.icm_epsilon * 0.1 * H || (sweep > 0 && value - last < 1e-4 * (1.0 + std::abs(value)))) break;
    last = value;
  }
}

Omega m_step(const SketchTree& t, const SketchDepths& d, const Omega& prev) {
  std::vector<SegmentAngles> a = segment_angles(t, d.z);
  std::vector<double> s, al, be;
  double gs = 0, gc = 0;
  std::vector<double> g;
  for (size_t c = 1; c < t.xy.size(); ++c) {
    if (!has_parent_segment(t, int(c))) continue;
    int label = std::max(d.label[c], 0), K = int(t.children[size_t(t.parent[c])].size());
    s.push_back(a[c].s);
    (label == 0 ? al : be).push_back(a[c].angle);
    double gamma = wrap(a[c].gamma - label_gamma_offset(label, K));
    g.push_back(gamma);
    gs += std::sin(gamma), gc += std::cos(gamma);
  }
  auto stats = [](const std::vector<double>& x, double& mu, double& sd, double floor) {
    if (x.empty()) return;
    mu = std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
    double var = 0.0;
    for (double v : x) var += (v - mu) * (v - mu);
    sd = std::max(std::sqrt(var / double(x.size())), floor);
  };
  Omega o = prev;
  const double deg = kPi / 180.0;
  stats(s, o.mu_s, o.sd_s, 0.02);
  stats(al, o.mu_a, o.sd_a, deg);
  stats(be, o.mu_b, o.sd_b, deg);
  if (!g.empty()) {
    o.mu_g = std::atan2(gs, gc);
    double var = 0.0;
    for (double v : g) var += wrap(v - o.mu_g) * wrap(v - o.mu_g);
    o.sd_g = std::max(std::sqrt(var / double(g.size())), deg);
  }
  return o;
}

InferenceResult infer_depths(const SketchTree& t, const Omega& initial, const InferenceParams& params) {
  InferenceResult r;
  r.omega = initial;
  r.omega_history.push_back(initial);
  for (int it = 0; it < std::max(1, params.em_iterations); ++it) {
    r.depths = infer_bottom_up(t, r.omega);
    separate_crossings(t, r.depths);
    refine_icm(t, r.depths, r.omega, params, &r.icm_log_p);
    r.em_iterations = it + 1;
    if (!params.estimate_omega) break;
    Omega next = m_step(t, r.depths, r.omega);
    double change = std::max({std::abs(next.mu_s - r.omega.mu_s), std::abs(next.sd_s - r.omega.sd_s),
                              std::abs(next.mu_a - r.omega.mu_a), std::abs(next.sd_a - r.omega.sd_a),
                              std::abs(next.mu_b - r.omega.mu_b), std::abs(next.sd_b - r.omega.sd_b),
                              std::abs(wrap(next.mu_g - r.omega.mu_g)), std::abs(next.sd_g - r.omega.sd_g)});
    r.omega = next;
    r.omega_history.push_back(next);
    if (change < 1e-4) break;
  }
  return r;
}

}  // namespace forest
