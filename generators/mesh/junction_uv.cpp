#include "generators/mesh/junction_uv.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <utility>

namespace forest {

namespace {

using Corners = std::array<JunctionUvCorner, 3>;
using Uvs = std::array<glm::vec2, 3>;

double signed_area(const Uvs& uv) {
  const glm::dvec2 a = uv[1] - uv[0], b = uv[2] - uv[0];
  return 0.5 * (a.x * b.y - a.y * b.x);
}

// The singular values of a triangle's uv map, times the tile: 1 and 1 when it has the
// texture's physical scale in every direction. False for a degenerate triangle.
bool stretch_ok(const Corners& c, const Uvs& uv, double tile, double tolerance) {
  const glm::dvec3 e1 = glm::dvec3(c[1].position - c[0].position), e2 = glm::dvec3(c[2].position - c[0].position);
  const double l1 = glm::length(e1);
  const glm::dvec3 n = glm::cross(e1, e2);
  if (!(l1 > 0.0) || !(glm::length(n) > 0.0)) return false;
  const glm::dvec3 x = e1 / l1, y = glm::normalize(glm::cross(glm::normalize(n), x));
  const glm::dmat2 p(glm::dvec2(l1, 0.0), glm::dvec2(glm::dot(e2, x), glm::dot(e2, y)));
  const glm::dmat2 q(glm::dvec2(uv[1] - uv[0]), glm::dvec2(uv[2] - uv[0]));
  const glm::dmat2 j = q * glm::inverse(p) * tile;
  const glm::dmat2 m = glm::transpose(j) * j;
  const double tr = m[0][0] + m[1][1], det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4.0 - det));
  const double lo = std::sqrt(std::max(0.0, tr / 2.0 - disc)), hi = std::sqrt(tr / 2.0 + disc);
  return lo >= 1.0 - tolerance && hi <= 1.0 + tolerance;
}

// u of a tube corner shifted by whole turns of its ring to lie nearest `near`.
glm::vec2 unwrapped(const JunctionUvCorner& c, float near) {
  glm::vec2 uv = c.tube_uv;
  if (c.period > 0.0f) uv.x += c.period * std::round((near - uv.x) / c.period);
  return uv;
}

// Corner k of t placed isometrically from corners i and j (already in uv), on the side that
// keeps the triangle clockwise in uv like the tubes'.
void unfold(const Corners& c, Uvs& uv, int i, int j, int k, double tile) {
  const glm::dvec3 e = glm::dvec3(c[j].position - c[i].position), q = glm::dvec3(c[k].position - c[i].position);
  const double len = glm::length(e);
  const glm::dvec2 d = glm::dvec2(uv[j] - uv[i]);
  const double dlen = glm::length(d);
  if (!(len > 0.0) || !(dlen > 0.0)) {
    uv[k] = uv[i];
    return;
  }
  const double x = glm::dot(q, e) / len, y = glm::length(q - e * (x / len));
  const glm::dvec2 along = d / dlen, across(-along.y, along.x);
  for (double side : {1.0, -1.0}) {
    uv[k] = glm::vec2(glm::dvec2(uv[i]) + (along * x + across * (side * y)) / tile);
    if (signed_area(uv) <= 0.0) return;
  }
}

int corner_of(const Corners& c, uint32_t vertex) {
  for (int k = 0; k < 3; ++k)
    if (c[k].vertex == vertex) return k;
  return -1;
}

// A triangle no placed neighbour reaches: its tube corners (if any) at their tube uv, the
// rest unfolded from them.
void seed(const Corners& c, Uvs& uv, double tile) {
  int first = -1, second = -1;
  for (int k = 0; k < 3; ++k) {
    if (!c[k].on_tube) continue;
    if (first < 0) first = k;
    else if (second < 0) second = k;
  }
  if (first < 0) first = 0;
  uv[first] = c[first].on_tube ? c[first].tube_uv : glm::vec2(0.0f);
  if (second < 0) {
    second = (first + 1) % 3;
    uv[second] = uv[first] + glm::vec2(float(glm::length(c[second].position - c[first].position) / tile), 0.0f);
  } else {
    uv[second] = unwrapped(c[second], uv[first].x);
  }
  unfold(c, uv, first, second, 3 - first - second, tile);
}

}  // namespace

std::vector<std::array<glm::vec2, 3>> junction_uvs(std::span<const std::array<JunctionUvCorner, 3>> tris,
                                                   float tile_meters, float tolerance) {
  const double tile = double(tile_meters);
  std::vector<Uvs> out(tris.size());
  std::vector<char> placed(tris.size(), 0);
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
  auto key = [](uint32_t a, uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (uint32_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) edges[key(tris[t][k].vertex, tris[t][(k + 1) % 3].vertex)].push_back(t);
  // The first uv each vertex got: a triangle placed later reuses it where it fits, so that
  // the junction shares vertices (and its texture is continuous) wherever it is nearly flat.
  std::map<uint32_t, glm::vec2> first_uv;
  auto fits = [&](const Corners& c, const Uvs& uv) {
    return signed_area(uv) < 0.0 && stretch_ok(c, uv, tile, double(tolerance));
  };
  auto place = [&](uint32_t t, const Uvs& uv, std::deque<uint32_t>& queue) {
    out[t] = uv, placed[t] = 1, queue.push_back(t);
    for (int k = 0; k < 3; ++k) first_uv.try_emplace(tris[t][k].vertex, uv[k]);
  };
  std::deque<uint32_t> queue;
  // The tubes' own uv where they fit.
  for (uint32_t t = 0; t < tris.size(); ++t) {
    const Corners& c = tris[t];
    if (!c[0].on_tube || !c[1].on_tube || !c[2].on_tube) continue;
    Uvs uv{c[0].tube_uv, unwrapped(c[1], c[0].tube_uv.x), unwrapped(c[2], c[0].tube_uv.x)};
    if (fits(c, uv)) place(t, uv, queue);
  }
  // Breadth-first across shared edges: the third corner keeps the uv it already has (or its
  // tube's) where the triangle fits, else it is unfolded. A part no placed triangle reaches
  // is seeded.
  for (uint32_t next_seed = 0;;) {
    while (!queue.empty()) {
      const uint32_t t = queue.front();
      queue.pop_front();
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tris[t][k].vertex, b = tris[t][(k + 1) % 3].vertex;
        for (uint32_t n : edges[key(a, b)]) {
          if (placed[n]) continue;
          const Corners& c = tris[n];
          const int i = corner_of(c, a), j = corner_of(c, b), m = 3 - i - j;
          Uvs uv;
          uv[i] = out[t][k];
          uv[j] = out[t][(k + 1) % 3];
          auto known = first_uv.find(c[m].vertex);
          bool done = false;
          if (known != first_uv.end()) uv[m] = known->second, done = fits(c, uv);
          if (!done && c[m].on_tube) uv[m] = unwrapped(c[m], uv[i].x), done = fits(c, uv);
          if (!done) unfold(c, uv, i, j, m, tile);
          place(n, uv, queue);
        }
      }
    }
    while (next_seed < tris.size() && placed[next_seed]) ++next_seed;
    if (next_seed == tris.size()) break;
    Uvs uv;
    seed(tris[next_seed], uv, tile);
    place(next_seed, uv, queue);
  }
  return out;
}

}  // namespace forest
