#include "generators/methods/sketch_mrf/sketch_propagation.h"

#include <algorithm>
#include <cmath>

#include "generators/core/rng.h"

namespace forest {

bool CrownSurface::contains(glm::dvec3 p) const {
  double xmin = 1e300, xmax = -1e300;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    glm::dvec2 a = polygon[i], b = polygon[(i + 1) % n];
    if ((a.y <= p.y && b.y >= p.y) || (b.y <= p.y && a.y >= p.y)) {
      double x = std::abs(b.y - a.y) < 1e-12 ? std::min(a.x, b.x) : a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
      xmin = std::min({xmin, x, std::abs(b.y - a.y) < 1e-12 ? std::min(a.x, b.x) : x});
      xmax = std::max({xmax, x, std::abs(b.y - a.y) < 1e-12 ? std::max(a.x, b.x) : x});
    }
  }
  if (xmin > xmax) return false;  // above or below the crown
  double right = std::max(xmax - axis_x, 0.0), left = std::max(axis_x - xmin, 0.0);
  double dx = p.x - axis_x, r = std::hypot(dx, p.z);
  if (r < 1e-12) return true;
  double c = dx / r;
  return r <= right * 0.5 * (1.0 + c) + left * 0.5 * (1.0 - c);
}

PropagatedTree propagate_branches(const SketchTree& t, const SketchDepths& d, const CrownSurface* crown,
                                  const PropagationParams& params, uint64_t seed) {
  PropagatedTree out;
  std::vector<SegmentFrame> frames = segment_frames(t, d.z);
  // Sketch nodes in breadth-first order so parents come first.
  std::vector<int> order{0}, new_index(t.xy.size(), -1);
  for (size_t k = 0; k < order.size(); ++k)
    for (int c : t.children[size_t(order[k])]) order.push_back(c);
  for (int i : order) {
    new_index[size_t(i)] = int(out.position.size());
    out.position.emplace_back(t.xy[size_t(i)].x, t.xy[size_t(i)].y, d.z[size_t(i)]);
    int p = t.parent[size_t(i)];
    out.parent.push_back(p < 0 ? -1 : new_index[size_t(p)]);
    out.order.push_back(p < 0 ? 0 : out.order[size_t(new_index[size_t(p)])] + (d.label[size_t(i)] > 0 ? 1 : 0));
    out.sketched.push_back(1);
  }
  std::vector<SegmentFrame> frame(out.position.size());
  for (int i : order) frame[size_t(new_index[size_t(i)])] = frames[size_t(i)];

  // Replication blocks: children of every segment that has a parent segment and children,
  // in the parent's frame, lengths relative to the parent's.
  struct Child { glm::dvec3 local; int label; };
  std::vector<std::vector<Child>> blocks;
  for (int p : order) {
    if (p == 0 || t.children[size_t(p)].empty()) continue;
    glm::dvec3 vp = glm::dvec3(t.xy[size_t(p)], d.z[size_t(p)]) -
                    glm::dvec3(t.xy[size_t(t.parent[size_t(p)])], d.z[size_t(t.parent[size_t(p)])]);
    double lp = glm::length(vp);
    if (lp < 1e-9) continue;
    const SegmentFrame& f = frames[size_t(p)];
    std::vector<Child> block;
    for (int c : t.children[size_t(p)]) {
      glm::dvec3 vc = glm::dvec3(t.xy[size_t(c)], d.z[size_t(c)]) - glm::dvec3(t.xy[size_t(p)], d.z[size_t(p)]);
      block.push_back({glm::dvec3(glm::dot(vc, f.t), glm::dot(vc, f.n), glm::dot(vc, f.b)) / lp,
                       std::max(d.label[size_t(c)], 0)});
    }
    blocks.push_back(std::move(block));
  }
  if (blocks.empty()) return out;

  std::vector<int> open;
  for (int i : order)
    if (i != 0 && t.children[size_t(i)].empty()) open.push_back(new_index[size_t(i)]);
  Rng rng(seed, /*stream=*/21);
  const double min_length = 1e-3 * t.height;
  for (int g = 0; g < params.generations && !open.empty(); ++g) {
    std::vector<int> next;
    for (int o : open) {
      if (out.position.size() >= params.max_segments) break;
      const std::vector<Child>& block = blocks[rng.next_u32() % blocks.size()];
      glm::dvec3 po = out.position[size_t(o)];
      double lo = glm::length(po - out.position[size_t(out.parent[size_t(o)])]);
      const SegmentFrame f = frame[size_t(o)];  // a copy: frame grows below
      for (const Child& c : block) {
        glm::dvec3 v = lo * (c.local.x * f.t + c.local.y * f.n + c.local.z * f.b);
        bool closed = false;
        if (crown && !crown->contains(po + v)) {
          if (!crown->contains(po)) continue;
          double a = 0.0, b = 1.0;  // largest scale that stays inside
          for (int it = 0; it < 30; ++it) {
            double m = 0.5 * (a + b);
            (crown->contains(po + m * v) ? a : b) = m;
          }
          v *= a;
          closed = true;
          ++out.closed_by_crown;
        }
        if (glm::length(v) < min_length) continue;
        out.position.push_back(po + v);
        out.parent.push_back(o);
        out.order.push_back(out.order[size_t(o)] + (c.label > 0 ? 1 : 0));
        out.sketched.push_back(0);
        frame.push_back(transport_frame(f, v));
        if (!closed) next.push_back(int(out.position.size()) - 1);
      }
    }
    open = std::move(next);
  }
  return out;
}

}  // namespace forest
