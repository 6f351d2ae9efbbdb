#include "generators/mesh/mesh_lod.h"

#include <algorithm>
#include <array>
#include <map>
#include <tuple>

#include <meshoptimizer.h>
#include <tbb/parallel_for.h>

namespace forest {

static_assert(sizeof(Vertex) == 32, "Vertex must be tightly packed for meshoptimizer");

namespace {

// An edge whose uv are this many times longer than its length at the bark's texel density
// crosses a texture seam (a smeared seam spans the branch's whole circumference in u).
constexpr float kSeamStretch = 2.0f;

// The surface welded by position: one vertex per distinct position, so that meshopt sees a
// manifold without attribute seams (whose vertices it would lock), and per welded vertex its
// LOD0 variants (the texture seam's two sides, the junctions' copies), in vertex order.
struct Welded {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<std::vector<uint32_t>> variants;
};

Welded weld(const Mesh& lod0) {
  std::vector<glm::vec3> pos(lod0.vertices.size());
  for (size_t i = 0; i < pos.size(); ++i) pos[i] = lod0.vertices[i].position;
  std::vector<uint32_t> remap(pos.size());
  size_t unique = meshopt_generateVertexRemap(remap.data(), nullptr, pos.size(), pos.data(), pos.size(), sizeof(glm::vec3));
  Welded w;
  w.positions.resize(unique);
  meshopt_remapVertexBuffer(w.positions.data(), pos.data(), pos.size(), sizeof(glm::vec3), remap.data());
  w.indices.resize(lod0.indices.size());
  meshopt_remapIndexBuffer(w.indices.data(), lod0.indices.data(), lod0.indices.size(), remap.data());
  w.variants.resize(unique);
  for (uint32_t v = 0; v < remap.size(); ++v) w.variants[remap[v]].push_back(v);
  return w;
}

// The bark's texel density (uv per metre: the median over LOD0's edges) and the winding of
// its triangles in uv (the sign of their summed signed uv area).
struct UvScale {
  float density = 0.0f;
  float winding = 1.0f;
};

float uv_area(const Vertex& a, const Vertex& b, const Vertex& c) {
  glm::vec2 e = b.uv - a.uv, f = c.uv - a.uv;
  return 0.5f * (e.x * f.y - e.y * f.x);
}

UvScale uv_scale(const Mesh& m) {
  std::vector<float> ratio;
  double area = 0.0;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const Vertex* v[3] = {&m.vertices[m.indices[t]], &m.vertices[m.indices[t + 1]], &m.vertices[m.indices[t + 2]]};
    area += double(uv_area(*v[0], *v[1], *v[2]));
    for (int k = 0; k < 3; ++k) {
      float len = glm::length(v[(k + 1) % 3]->position - v[k]->position);
      if (len > 0.0f) ratio.push_back(glm::length(v[(k + 1) % 3]->uv - v[k]->uv) / len);
    }
  }
  UvScale s;
  s.winding = area < 0.0 ? -1.0f : 1.0f;
  if (ratio.empty()) return s;
  std::nth_element(ratio.begin(), ratio.begin() + long(ratio.size() / 2), ratio.end());
  s.density = ratio[ratio.size() / 2];
  return s;
}

// An edge's uv length over its length at the bark's density (1: to scale).
float stretch(const Vertex& a, const Vertex& b, float density) {
  return (glm::length(b.uv - a.uv) + 1e-7f) / (glm::length(b.position - a.position) * density + 1e-7f);
}

// Corner k of triangle t re-placed as a new vertex whose uv unfold the triangle from its
// edge (i, j) at the bark's scale and winding: the triangle then continues that edge's side
// of the seam.
void unfold_corner(uint32_t* t, int i, int j, int k, std::vector<Vertex>& vertices, const UvScale& s) {
  const Vertex &a = vertices[t[i]], &b = vertices[t[j]];
  Vertex p = vertices[t[k]];
  const glm::vec3 e = b.position - a.position, q = p.position - a.position;
  const float len = glm::length(e), uv_len = glm::length(b.uv - a.uv);
  if (!(len > 0.0f) || !(uv_len > 0.0f)) return;
  const float x = glm::dot(q, e) / len, y = glm::length(q - e * (x / len));
  const glm::vec2 along = (b.uv - a.uv) / uv_len, across(-along.y, along.x);
  const Vertex* c[3];
  for (float side : {1.0f, -1.0f}) {
    p.uv = a.uv + (along * x + across * (side * y)) * s.density;
    c[i] = &a, c[j] = &b, c[k] = &p;
    if (uv_area(*c[0], *c[1], *c[2]) * s.winding >= 0.0f) break;
  }
  t[k] = uint32_t(vertices.size());
  vertices.push_back(p);
}

// Each simplified triangle's corners (welded vertices) become the LOD0 variants whose uv
// agree best (least squared stretch of its edges). A triangle that still crosses a seam (its
// seam vertex was collapsed away) keeps its edge closest to scale and unfolds its third
// corner from it.
void choose_variants(const Mesh& lod0, const Welded& w, const UvScale& s, std::vector<uint32_t>& indices,
                     std::vector<Vertex>& vertices) {
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::vector<uint32_t>* c[3] = {&w.variants[indices[t]], &w.variants[indices[t + 1]], &w.variants[indices[t + 2]]};
    float best = 1e30f;
    uint32_t pick[3] = {(*c[0])[0], (*c[1])[0], (*c[2])[0]};
    for (uint32_t a : *c[0])
      for (uint32_t b : *c[1])
        for (uint32_t d : *c[2]) {
          const uint32_t v[3] = {a, b, d};
          float cost = 0.0f;
          for (int k = 0; k < 3; ++k) {
            float e = stretch(lod0.vertices[v[k]], lod0.vertices[v[(k + 1) % 3]], s.density) - 1.0f;
            cost += e * e;
          }
          if (cost < best) best = cost, pick[0] = a, pick[1] = b, pick[2] = d;
        }
    std::copy(pick, pick + 3, &indices[t]);
    float edge[3], worst = 0.0f;
    int keep = 0;
    for (int k = 0; k < 3; ++k) {
      edge[k] = stretch(vertices[pick[k]], vertices[pick[(k + 1) % 3]], s.density);
      worst = std::max(worst, edge[k]);
      if (std::abs(edge[k] - 1.0f) < std::abs(edge[keep] - 1.0f)) keep = k;
    }
    if (worst > kSeamStretch && s.density > 0.0f) unfold_corner(&indices[t], keep, (keep + 1) % 3, (keep + 2) % 3, vertices, s);
  }
}

}  // namespace

void optimize_mesh(Mesh& mesh) {
  if (mesh.indices.empty() || mesh.vertices.empty()) return;
  std::vector<uint32_t> indices(mesh.indices.size());
  meshopt_optimizeVertexCache(indices.data(), mesh.indices.data(), mesh.indices.size(), mesh.vertices.size());
  std::vector<Vertex> vertices(mesh.vertices.size());
  size_t used = meshopt_optimizeVertexFetch(vertices.data(), indices.data(), indices.size(),
                                            mesh.vertices.data(), mesh.vertices.size(), sizeof(Vertex));
  vertices.resize(used);
  mesh.vertices = std::move(vertices);
  mesh.indices = std::move(indices);
}

namespace {

// simplify_to and sloppy_lod: `source` welded by position, simplified by edge collapses
// within max_error metres (sloppy: by vertex clustering, the count alone stopping it), the
// corners then taking the source variants whose uv fit.
MeshLod simplified(const Mesh& source, size_t target_triangles, float max_error, bool sloppy) {
  MeshLod lod;
  if (source.indices.empty()) return lod;
  const Welded welded = weld(source);
  const UvScale uv = uv_scale(source);
  const float scale = meshopt_simplifyScale(&welded.positions[0].x, welded.positions.size(), sizeof(glm::vec3));
  std::vector<uint32_t> indices(welded.indices.size());
  float relative = 0.0f;
  const size_t target = std::min(welded.indices.size(), std::max<size_t>(1, target_triangles) * 3);
  const size_t count =
      sloppy ? meshopt_simplifySloppy(indices.data(), welded.indices.data(), welded.indices.size(),
                                      &welded.positions[0].x, welded.positions.size(), sizeof(glm::vec3), target,
                                      1.0f, &relative)
             : meshopt_simplify(indices.data(), welded.indices.data(), welded.indices.size(), &welded.positions[0].x,
                                welded.positions.size(), sizeof(glm::vec3), target,
                                scale > 0.0f ? max_error / scale : 0.0f, meshopt_SimplifyLockBorder, &relative);
  indices.resize(count);
  lod.mesh.vertices = source.vertices;
  choose_variants(source, welded, uv, indices, lod.mesh.vertices);
  lod.mesh.indices = std::move(indices);
  if (sloppy) remove_back_to_back(lod.mesh);
  optimize_mesh(lod.mesh);
  if (lod.mesh.indices.empty()) lod.mesh.vertices.clear();
  lod.error = relative * scale;
  return lod;
}

}  // namespace

MeshLod simplify_to(const Mesh& source, size_t target_triangles, float max_error) {
  return simplified(source, target_triangles, max_error, false);
}

std::vector<float> collapse_errors(const Mesh& mesh, std::span<const size_t> targets, float max_error) {
  std::vector<float> errors(targets.size(), 0.0f);
  if (mesh.indices.empty()) return errors;
  const Welded welded = weld(mesh);
  const float scale = meshopt_simplifyScale(&welded.positions[0].x, welded.positions.size(), sizeof(glm::vec3));
  tbb::parallel_for(size_t(0), targets.size(), [&](size_t i) {
    std::vector<uint32_t> indices(welded.indices.size());
    float relative = 0.0f;
    meshopt_simplify(indices.data(), welded.indices.data(), welded.indices.size(), &welded.positions[0].x,
                     welded.positions.size(), sizeof(glm::vec3),
                     std::min(welded.indices.size(), std::max<size_t>(1, targets[i]) * 3),
                     scale > 0.0f ? max_error / scale : 0.0f, meshopt_SimplifyLockBorder, &relative);
    errors[i] = relative * scale;
  });
  return errors;
}

std::vector<MeshLod> simplify_lods(const Mesh& lod0, std::span<const float> fractions,
                                   float max_relative_error) {
  std::vector<MeshLod> lods;
  if (lod0.indices.empty()) return lods;
  const float scale = meshopt_simplifyScale(&lod0.vertices[0].position.x, lod0.vertices.size(), sizeof(Vertex));
  const size_t triangles0 = lod0.indices.size() / 3;
  size_t previous = triangles0;
  float error = 0.0f;
  for (float fraction : fractions) {
    MeshLod lod = simplify_to(lod0, size_t(double(triangles0) * double(fraction)), max_relative_error * scale);
    const size_t triangles = lod.mesh.indices.size() / 3;
    if (triangles == 0 || triangles * 10 > previous * 9) break;
    error = std::max(error, lod.error);
    lod.error = error;
    lods.push_back(std::move(lod));
    previous = triangles;
  }
  return lods;
}

namespace {

// A triangle by its corner positions: the sorted corners (the key shared by both windings)
// and its winding relative to that order.
using Corner = std::tuple<float, float, float>;
struct TriangleKey {
  std::array<Corner, 3> sorted;
  bool flipped = false;
};

TriangleKey triangle_key(const Mesh& m, size_t t) {
  std::array<Corner, 3> c;
  for (size_t k = 0; k < 3; ++k) {
    const glm::vec3& p = m.vertices[m.indices[t + k]].position;
    c[k] = {p.x, p.y, p.z};
  }
  // Rotate to start at the smallest corner (winding kept); the winding is then whether the
  // second corner is the smaller of the other two.
  size_t first = size_t(std::min_element(c.begin(), c.end()) - c.begin());
  const Corner& b = c[(first + 1) % 3];
  const Corner& d = c[(first + 2) % 3];
  TriangleKey key;
  key.flipped = d < b;
  key.sorted = c;
  std::sort(key.sorted.begin(), key.sorted.end());
  return key;
}

// Per corner-position set, the triangles (index of their first index) of each winding.
std::map<std::array<Corner, 3>, std::array<std::vector<size_t>, 2>> triangles_by_corners(const Mesh& m) {
  std::map<std::array<Corner, 3>, std::array<std::vector<size_t>, 2>> groups;
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    TriangleKey k = triangle_key(m, t);
    groups[k.sorted][k.flipped ? 1 : 0].push_back(t);
  }
  return groups;
}

}  // namespace

size_t count_back_to_back(const Mesh& mesh) {
  size_t n = 0;
  for (const auto& [corners, sides] : triangles_by_corners(mesh))
    if (!sides[0].empty() && !sides[1].empty()) n += sides[0].size() + sides[1].size();
  return n;
}

size_t remove_back_to_back(Mesh& mesh) {
  std::vector<char> drop(mesh.indices.size() / 3, 0);
  for (const auto& [corners, sides] : triangles_by_corners(mesh)) {
    // Opposite windings cancel pair by pair; of what is left of one winding, one copy stays.
    const size_t a = sides[0].size(), b = sides[1].size();
    const int keep_side = a > b ? 0 : (b > a ? 1 : -1);
    for (int s = 0; s < 2; ++s)
      for (size_t i = 0; i < sides[size_t(s)].size(); ++i)
        if (s != keep_side || i > 0) drop[sides[size_t(s)][i] / 3] = 1;
  }
  std::vector<uint32_t> kept;
  kept.reserve(mesh.indices.size());
  for (size_t t = 0; t < drop.size(); ++t)
    if (!drop[t]) kept.insert(kept.end(), {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]});
  const size_t removed = (mesh.indices.size() - kept.size()) / 3;
  mesh.indices = std::move(kept);
  return removed;
}

MeshLod sloppy_lod(const Mesh& source, size_t target_triangles) {
  return simplified(source, target_triangles, 0.0f, true);
}

}  // namespace forest
