#include "generators/methods/silhouettes/silhouettes_branches.h"

#include <algorithm>
#include <cmath>

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

double cross(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

double angle_between_deg(glm::dvec2 a, glm::dvec2 b) {
  double la = glm::length(a), lb = glm::length(b);
  if (la <= 0 || lb <= 0) return 0.0;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) * 180.0 / kPi;
}

double curve_length(const std::vector<glm::dvec2>& c) {
  double s = 0.0;
  for (size_t k = 1; k < c.size(); ++k) s += glm::length(c[k] - c[k - 1]);
  return s;
}

Polygon2 resample_closed(const Polygon2& poly, int n) {
  std::vector<glm::dvec2> closed = poly;
  closed.push_back(poly.front());
  Polyline2 line(closed);
  Polygon2 out;
  for (int k = 0; k < n; ++k) out.push_back(line.at(double(k) / n));
  return out;
}

}  // namespace

BranchingAngleFunction BranchingAngleFunction::linear(double bottom, double top) {
  BranchingAngleFunction f;
  f.samples = {{0.0, bottom}, {1.0, top}};
  return f;
}

double BranchingAngleFunction::operator()(double t) const {
  if (samples.empty()) return 45.0;
  if (t <= samples.front().first) return samples.front().second;
  if (t >= samples.back().first) return samples.back().second;
  for (size_t k = 1; k < samples.size(); ++k)
    if (t <= samples[k].first) {
      auto [t0, a0] = samples[k - 1];
      auto [t1, a1] = samples[k];
      return t1 > t0 ? a0 + (a1 - a0) * (t - t0) / (t1 - t0) : a1;
    }
  return samples.back().second;
}

void BranchingAngleFunction::add_sample(double t, double degrees) {
  for (auto& s : samples)
    if (std::abs(s.first - t) < 1e-9) {
      s.second = degrees;
      return;
    }
  samples.emplace_back(t, degrees);
  std::sort(samples.begin(), samples.end());
}

glm::dvec2 rotate(glm::dvec2 d, double degrees) {
  double a = degrees * kPi / 180.0, c = std::cos(a), s = std::sin(a);
  return {c * d.x - s * d.y, s * d.x + c * d.y};
}

Branch2D infer_branch(const Polyline2& axis, const Bump& bump, const BranchingAngleFunction& baf, double t_lo,
                      int samples) {
  Branch2D best;
  double best_length = 1e300;
  samples = std::max(samples, 2);
  for (int i = 0; i < samples; ++i) {
    double t = t_lo + (1.0 - t_lo) * double(i) / double(samples - 1);
    glm::dvec2 b = axis.at(t), tangent = axis.tangent(t);
    double span = glm::length(bump.end - b);
    if (span < 1e-9) continue;
    int side = cross(tangent, bump.end - b) > 0 ? -1 : 1;  // E left of the axis -> left side
    glm::dvec2 m0 = rotate(tangent, -side * baf(t)) * (0.5 * span);
    glm::dvec2 m1 = bump.tangent * (0.5 * span);
    std::vector<glm::dvec2> curve = hermite_polyline(b, m0, bump.end, m1, 16);
    double len = curve_length(curve);
    if (len < best_length) {
      best_length = len;
      best.curve = std::move(curve);
      best.t = t;
      best.side = side;
      best.start_tangent = m0 / glm::length(m0);
      best.end_radius = bump.radius;
    }
  }
  return best;
}

std::vector<glm::dvec2> span_transfer(const std::vector<glm::dvec2>& source, glm::dvec2 tb, glm::dvec2 te) {
  glm::dvec2 sb = source.front(), span_s = source.back() - sb, span_t = te - tb;
  double ls = glm::length(span_s), lt = glm::length(span_t);
  if (ls < 1e-12) return std::vector<glm::dvec2>(source.size(), tb);
  glm::dvec2 xs = span_s / ls, ys(-xs.y, xs.x);
  glm::dvec2 xt = lt > 0 ? span_t / lt : xs, yt(-xt.y, xt.x);
  double scale = lt / ls;
  std::vector<glm::dvec2> out;
  for (glm::dvec2 p : source) {
    glm::dvec2 d = p - sb;
    out.push_back(tb + scale * (glm::dot(d, xs) * xt + glm::dot(d, ys) * yt));
  }
  return out;
}

double sub_silhouette_cone_deg(double r, double d) {
  double ratio = d > 0 ? r / d : 1.0;
  double a = std::clamp((ratio - 0.1) / 0.5, 0.0, 1.0);
  return 20.0 + a * 90.0;
}

Polygon2 infer_sub_silhouette(const Polygon2& parent, glm::dvec2 base, glm::dvec2 end, double end_radius) {
  if (parent.size() < 3) return {};
  Polygon2 poly = resample_closed(parent, 240);
  const int n = int(poly.size());
  double d = glm::length(end - base);
  if (d < 1e-9) return {};
  glm::dvec2 axis = (end - base) / d;
  double half = 0.5 * sub_silhouette_cone_deg(end_radius, d);
  auto in_cone = [&](int k) {
    glm::dvec2 v = poly[size_t(k)] - base;
    return glm::length(v) >= 0.3 * d && angle_between_deg(v, axis) <= half;
  };
  // The vertex where the ray B -> E leaves the silhouette: smallest angle among far ones.
  int k0 = -1;
  double best = 1e300;
  for (int k = 0; k < n; ++k) {
    glm::dvec2 v = poly[size_t(k)] - base;
    if (glm::length(v) < 0.8 * d) continue;
    double a = angle_between_deg(v, axis);
    if (a < best) best = a, k0 = k;
  }
  if (k0 < 0) return {};
  int lo = 0, hi = 0;  // run = k0 + [lo, hi]
  while (hi - lo < n - 1 && in_cone(((k0 + hi + 1) % n + n) % n)) ++hi;
  while (hi - lo < n - 1 && in_cone(((k0 + lo - 1) % n + n) % n)) --lo;
  if (hi - lo < 2) lo -= 1, hi += 1;
  Polygon2 out;
  for (int k = lo; k <= hi; ++k) out.push_back(poly[size_t(((k0 + k) % n + n) % n)]);
  glm::dvec2 run_start = out.front(), run_end = out.back();
  auto forward = [&](int k) {  // polygon direction at run index k
    glm::dvec2 a = poly[size_t(((k0 + k - 1) % n + n) % n)], b = poly[size_t(((k0 + k + 1) % n + n) % n)];
    return glm::length(b - a) > 0 ? glm::normalize(b - a) : axis;
  };
  // G1 with the shared edges at both joints; the curves meet at the branch base B.
  double c1 = glm::length(base - run_end), c2 = glm::length(run_start - base);
  std::vector<glm::dvec2> back = hermite_polyline(run_end, forward(hi) * (0.5 * c1), base,
                                                  glm::normalize(base - run_end) * (0.5 * c1), 12);
  std::vector<glm::dvec2> up = hermite_polyline(base, glm::normalize(run_start - base) * (0.5 * c2), run_start,
                                                forward(lo) * (0.5 * c2), 12);
  out.insert(out.end(), back.begin() + 1, back.end());
  out.insert(out.end(), up.begin() + 1, up.end() - 1);
  return out;
}

std::vector<Branch2D> fill_in(const Polyline2& axis, const Polygon2& parent_sil, const std::vector<Branch2D>& siblings,
                              const BranchingAngleFunction& baf, double t_lo, int samples, double max_overlap) {
  std::vector<Branch2D> added;
  if (siblings.empty() || samples < 1) return added;
  std::vector<Polygon2> crowns;
  for (const Branch2D& b : siblings)
    if (b.crown.size() >= 3) crowns.push_back(b.crown);
  for (int i = 0; i < samples; ++i) {
    double t = t_lo + (1.0 - t_lo) * (double(i) + 0.5) / double(samples);
    for (int side : {-1, 1}) {
      const Branch2D* src = &siblings[0];
      for (const Branch2D& b : siblings)
        if (std::abs(b.t - t) < std::abs(src->t - t)) src = &b;
      if (src->curve.size() < 2) continue;
      glm::dvec2 bs = src->curve.front(), ts = axis.tangent(src->t);
      glm::dvec2 bk = axis.at(t), tk = axis.tangent(t);
      double a_src = angle_between_deg(ts, src->curve[1] - src->curve[0]);
      // Source frame (tangent, normal toward its side) -> target frame, then BAF rotation.
      glm::dvec2 ns = rotate(ts, -90.0 * src->side), nk = rotate(tk, -90.0 * side);
      double turn = -side * (baf(t) - a_src);
      auto map = [&](glm::dvec2 p, double scale) {
        glm::dvec2 d = p - bs;
        glm::dvec2 local = glm::dot(d, ts) * tk + glm::dot(d, ns) * nk;
        return bk + scale * rotate(local, turn);
      };
      for (double scale = 1.0; scale > 0.25; scale -= 0.1) {
        Branch2D b;
        b.t = t;
        b.side = side;
        b.filled = true;
        b.end_radius = src->end_radius * scale;
        for (glm::dvec2 p : src->curve) b.curve.push_back(map(p, scale));
        for (glm::dvec2 p : src->crown) b.crown.push_back(map(p, scale));
        bool fits = true;
        for (glm::dvec2 p : b.curve) fits = fits && point_in_polygon(parent_sil, p);
        for (size_t k = 0; k < b.crown.size() && fits; k += 4) fits = point_in_polygon(parent_sil, b.crown[k]);
        if (!fits) continue;
        if (crown_overlap(b.crown, crowns) <= max_overlap) {
          crowns.push_back(b.crown);
          added.push_back(std::move(b));
        }
        break;  // the largest fitting copy is the candidate at this position
      }
    }
  }
  return added;
}

}  // namespace forest
