#include "generators/methods/visual_hull/outline_tips.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace forest {

namespace {

double cross(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

double line_distance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  double len = glm::length(b - a);
  return len > 1e-12 ? std::abs(cross(a, b, p)) / len : glm::length(p - a);
}

// Indices (into `pts`) of the convex hull vertices (Andrew's monotone chain, no collinear
// points), in increasing index order: along the chain, which for a simple outline is the
// hull's cyclic order. Repeated points count once (their first index).
std::vector<size_t> hull_indices(const std::vector<glm::dvec2>& pts) {
  std::vector<size_t> order(pts.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    glm::dvec2 p = pts[a], q = pts[b];
    return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && a < b)));
  });
  order.erase(std::unique(order.begin(), order.end(), [&](size_t a, size_t b) { return pts[a] == pts[b]; }),
              order.end());
  if (order.size() < 3) return order;
  std::vector<size_t> h(2 * order.size());
  size_t k = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    while (k >= 2 && cross(pts[h[k - 2]], pts[h[k - 1]], pts[order[i]]) <= 0) --k;
    h[k++] = order[i];
  }
  for (size_t i = order.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(pts[h[k - 2]], pts[h[k - 1]], pts[order[i]]) <= 0) --k;
    h[k++] = order[i];
  }
  h.resize(k - 1);
  std::sort(h.begin(), h.end());
  return h;
}

struct Walker {
  const std::vector<glm::dvec2>& outline;
  const OutlineTipParams& params;
  double min_depth;
  std::vector<OutlineTip>& tips;

  // `chain` (outline points in order) is closed by the segment from its last point back to its
  // first, which is an edge of the parent's hull. `pocket`: the region it bounds is empty
  // space (so what falls back from its hull is tree) or tree (what falls back is a pocket).
  // `level` is the chain's own level; what falls back from its hull is one level deeper.
  void visit(const std::vector<glm::dvec2>& chain, bool pocket, int level) {
    if (level + 1 > params.max_level || chain.size() < 3) return;
    std::vector<size_t> h = hull_indices(chain);
    for (size_t k = 0; k + 1 < h.size(); ++k) {  // the edge back from h.back() is the closing one
      // A part that starts at an end of the chain is the flank of the lobe (or pocket) that
      // bounds this one, bulging past the hull edge: not a new part.
      if (h[k] == 0 || h[k + 1] == chain.size() - 1) continue;
      glm::dvec2 a = chain[h[k]], b = chain[h[k + 1]];
      double depth = 0.0;
      size_t deepest = h[k];
      for (size_t i = h[k]; i <= h[k + 1]; ++i) {
        double d = line_distance(chain[i], a, b);
        if (d > depth) depth = d, deepest = i;
      }
      if (depth < min_depth) continue;
      if (pocket) tips.push_back({chain[deepest], level + 1, depth});
      std::vector<glm::dvec2> sub(chain.begin() + ptrdiff_t(h[k]), chain.begin() + ptrdiff_t(h[k + 1]) + 1);
      visit(sub, !pocket, level + 1);
    }
  }
};

}  // namespace

std::vector<glm::dvec2> trace_outline(const Mask& m) {
  // Largest 8-connected component (ties: the first in raster order).
  std::vector<int> label(size_t(m.width) * size_t(m.height), -1);
  int best = -1;
  size_t best_size = 0, best_start = 0;
  std::vector<size_t> stack;
  for (size_t s = 0; s < label.size(); ++s) {
    int si = int(s % size_t(m.width)), sj = int(s / size_t(m.width));
    if (label[s] >= 0 || !m.inside(si, sj)) continue;
    int id = int(s);
    size_t size = 0;
    stack = {s};
    label[s] = id;
    while (!stack.empty()) {
      size_t c = stack.back();
      stack.pop_back();
      ++size;
      int ci = int(c % size_t(m.width)), cj = int(c / size_t(m.width));
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          int ni = ci + di, nj = cj + dj;
          if (!m.inside(ni, nj)) continue;
          size_t n = size_t(nj) * size_t(m.width) + size_t(ni);
          if (label[n] < 0) label[n] = id, stack.push_back(n);
        }
    }
    if (size > best_size) best_size = size, best = id, best_start = s;
  }
  if (best < 0) return {};
  auto in = [&](glm::ivec2 p) {
    return m.inside(p.x, p.y) && label[size_t(p.y) * size_t(m.width) + size_t(p.x)] == best;
  };
  // Moore-neighbour tracing from the top-left pixel (its west neighbour is outside), with
  // Jacob's stopping criterion: stop on re-entering the start the way we first left it.
  static const glm::ivec2 kDir[8] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  auto dir_of = [](glm::ivec2 d) {
    for (int k = 0; k < 8; ++k)
      if (kDir[k] == d) return k;
    return 0;
  };
  const glm::ivec2 start(int(best_start % size_t(m.width)), int(best_start / size_t(m.width)));
  std::vector<glm::dvec2> out = {glm::dvec2(start) + 0.5};
  glm::ivec2 c = start;
  int back = 4;  // direction from c to its backtrack pixel (west)
  int first_move = -1;
  const size_t limit = 4 * label.size() + 8;
  for (size_t step = 0; step < limit; ++step) {
    int move = -1;
    for (int k = 1; k <= 8; ++k) {
      int d = (back + k) % 8;
      if (in(c + kDir[d])) {
        move = d;
        break;
      }
    }
    if (move < 0) break;  // a single pixel
    if (c == start) {
      if (first_move < 0) first_move = move;
      else if (move == first_move) break;
    }
    glm::ivec2 next = c + kDir[move];
    glm::ivec2 examined = c + kDir[(move + 7) % 8];  // the outside pixel checked just before
    back = dir_of(examined - next);
    c = next;
    if (c == start) continue;  // closed; the loop decides whether to go round again
    out.push_back(glm::dvec2(c) + 0.5);
  }
  return out;
}

std::vector<OutlineTip> outline_tips(const Mask& m, const OutlineTipParams& params,
                                     std::optional<glm::dvec2> base, int count) {
  std::vector<glm::dvec2> outline = trace_outline(m);
  std::vector<OutlineTip> tips;
  if (outline.size() < 3) {
    if (!outline.empty()) tips.push_back({outline[0], 0, 0.0});
    return tips;
  }
  const double area = double(m.count_inside());
  const double min_depth = std::max(1.5, params.pocket_depth * std::sqrt(area));
  std::vector<size_t> h = hull_indices(outline);
  const size_t hn = h.size();
  if (hn < 3) {
    tips.push_back({outline[h[0]], 0, 0.0});
    return tips;
  }
  double perimeter = 0.0;
  for (size_t k = 0; k < hn; ++k) perimeter += glm::length(outline[h[(k + 1) % hn]] - outline[h[k]]);
  // Level 0: pocket depth of every hull edge k (from h[k] to h[k+1] along the outline).
  auto chain_of = [&](size_t k) {
    std::vector<glm::dvec2> c;
    for (size_t i = h[k];; i = (i + 1) % outline.size()) {
      c.push_back(outline[i]);
      if (i == h[(k + 1) % hn]) break;
    }
    return c;
  };
  std::vector<double> depth(hn, 0.0);
  std::vector<uint8_t> significant(hn, 0);
  for (size_t k = 0; k < hn; ++k) {
    glm::dvec2 a = outline[h[k]], b = outline[h[(k + 1) % hn]];
    for (glm::dvec2 p : chain_of(k)) depth[k] = std::max(depth[k], line_distance(p, a, b));
    significant[k] = depth[k] >= min_depth || glm::length(b - a) >= params.long_edge * perimeter;
  }
  // The foot: both ends of the hull edge nearest to the base.
  std::vector<uint8_t> foot(hn, 0);
  if (base) {
    size_t nearest = 0;
    double bd = 1e300;
    for (size_t k = 0; k < hn; ++k) {
      glm::dvec2 a = outline[h[k]], b = outline[h[(k + 1) % hn]], ab = b - a;
      double t = std::clamp(glm::dot(*base - a, ab) / std::max(glm::dot(ab, ab), 1e-300), 0.0, 1.0);
      double d = glm::length(*base - (a + t * ab));
      if (d < bd) bd = d, nearest = k;
    }
    foot[nearest] = foot[(nearest + 1) % hn] = 1;
  }
  // Caps: runs of hull vertices between significant edges; tip = the outline point of the
  // run farthest out from its chord (the middle of the run when it is flat).
  size_t first = hn;
  for (size_t k = 0; k < hn; ++k)
    if (significant[k]) {
      first = (k + 1) % hn;  // a cap starts after a significant edge
      break;
    }
  if (first == hn) {  // convex, no pockets: one cap, its tip the farthest point from the foot
    glm::dvec2 from = base.value_or(glm::dvec2(outline[h[0]].x, double(m.height)));
    size_t far = h[0];
    for (size_t i : h)
      if (glm::length(outline[i] - from) > glm::length(outline[far] - from)) far = i;
    tips.push_back({outline[far], 0, 0.0});
  } else {
    for (size_t s = 0; s < hn;) {
      size_t v0 = (first + s) % hn, n = 1;
      bool is_foot = foot[v0];
      while (!significant[(v0 + n - 1) % hn]) is_foot = is_foot || foot[(v0 + n) % hn], ++n;
      s += n;
      if (is_foot) continue;
      size_t v1 = (v0 + n - 1) % hn;
      std::vector<glm::dvec2> run;
      for (size_t i = h[v0];; i = (i + 1) % outline.size()) {
        run.push_back(outline[i]);
        if (i == h[v1]) break;
      }
      glm::dvec2 tip = run[run.size() / 2];
      double out = 1.0;  // flatter than a pixel: keep the middle
      for (glm::dvec2 p : run)
        if (double d = line_distance(p, run.front(), run.back()); d > out) out = d, tip = p;
      double pocket = std::max(depth[(v0 + hn - 1) % hn], depth[v1]);
      tips.push_back({tip, 0, pocket});
    }
  }
  // Deeper levels inside every deep pocket.
  Walker walker{outline, params, min_depth, tips};
  for (size_t k = 0; k < hn; ++k)
    if (depth[k] >= min_depth) walker.visit(chain_of(k), true, 1);

  std::stable_sort(tips.begin(), tips.end(), [](const OutlineTip& a, const OutlineTip& b) {
    return a.level != b.level ? a.level < b.level : a.depth > b.depth;
  });
  const double sep = params.min_separation * std::hypot(double(m.width), double(m.height));
  std::vector<OutlineTip> kept;
  for (const OutlineTip& t : tips) {
    if (count >= 0 && int(kept.size()) >= count) break;
    bool far = true;
    for (const OutlineTip& k : kept) far = far && glm::length(k.pixel - t.pixel) >= sep;
    if (far) kept.push_back(t);
  }
  return kept;
}

}  // namespace forest
