// Metaball hull (Neubert 2012 §7.3.1): field, marching cubes, closedness, winding, containment,
// sample points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "generators/bake/hull/hull.h"
#include "generators/bake/hull/hull_field.h"
#include "generators/bake/hull/hull_nearest.h"
#include "generators/bake/hull/marching_cubes.h"
#include "generators/core/input_error.h"
#include "generators/core/rng.h"

using namespace forest;

namespace {

glm::quat random_rotation(Rng& rng) {
  glm::vec4 q(float(rng.symmetric()), float(rng.symmetric()), float(rng.symmetric()), float(rng.symmetric()));
  q = glm::normalize(q + glm::vec4(1e-3f));
  return glm::quat(q.w, q.x, q.y, q.z);
}

// A crown: an ellipsoid of leaves with a denser core, plus a few isolated leaves (separate
// hull components), plus a few hundred leaves on a thin "branch" line.
std::vector<LeafPlacement> crown(size_t n, uint64_t seed) {
  Rng rng(seed, 7);
  std::vector<LeafPlacement> leaves;
  for (size_t i = 0; i < n; ++i) {
    glm::vec3 p;
    do p = glm::vec3(rng.symmetric(), rng.symmetric(), rng.symmetric());
    while (glm::dot(p, p) > 1.0f);
    LeafPlacement l;
    l.position = glm::vec3(0.0f, 3.0f, 0.0f) + p * glm::vec3(1.5f, 1.2f, 1.0f);
    l.rotation = random_rotation(rng);
    l.scale = 0.08f;
    leaves.push_back(l);
  }
  for (int i = 0; i < 5; ++i) {
    LeafPlacement l;
    l.position = glm::vec3(2.5f + 0.6f * float(i), 1.0f + 0.3f * float(i), -1.0f);
    l.scale = 0.05f;
    leaves.push_back(l);
  }
  for (int i = 0; i < 200; ++i) {
    LeafPlacement l;
    l.position = glm::vec3(-2.0f + 0.01f * float(i), 0.5f + 0.004f * float(i), 0.8f);
    l.rotation = random_rotation(rng);
    l.scale = 0.04f;
    leaves.push_back(l);
  }
  return leaves;
}

// Calls fn(a, b, c) with the corners of every triangle, in double precision.
template <class Fn>
void for_each_triangle(const Mesh& m, Fn&& fn) {
  for (size_t t = 0; t < m.indices.size(); t += 3)
    fn(glm::dvec3(m.vertices[m.indices[t]].position), glm::dvec3(m.vertices[m.indices[t + 1]].position),
       glm::dvec3(m.vertices[m.indices[t + 2]].position));
}

double signed_volume(const Mesh& m) {
  double v = 0.0;
  for_each_triangle(m, [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) { v += glm::dot(a, glm::cross(b, c)) / 6.0; });
  return v;
}

double area(const Mesh& m) {
  double s = 0.0;
  for_each_triangle(m, [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) { s += 0.5 * glm::length(glm::cross(b - a, c - a)); });
  return s;
}

// Closed and consistently oriented: every directed edge occurs exactly once and its reverse
// exactly once (so every undirected edge is shared by exactly two triangles).
void expect_closed_oriented(const Mesh& m) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  ASSERT_GT(m.indices.size(), 0u);
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.indices.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = m.indices[t + k], b = m.indices[t + (k + 1) % 3];
      ASSERT_NE(a, b) << "degenerate index triangle " << t / 3;
      ++directed[{a, b}];
    }
  size_t bad = 0;
  for (const auto& [e, count] : directed) {
    auto rev = directed.find({e.second, e.first});
    if (count != 1 || rev == directed.end() || rev->second != 1) ++bad;
  }
  EXPECT_EQ(bad, 0u) << "of " << directed.size() << " directed edges";
}

// Ray parity with a majority over three generic directions (robust to grazing an edge).
bool inside_mesh(const Mesh& m, glm::dvec3 p) {
  const glm::dvec3 dirs[3] = {glm::normalize(glm::dvec3(0.5377, 0.8322, 0.1358)),
                              glm::normalize(glm::dvec3(-0.3317, 0.2138, 0.9188)),
                              glm::normalize(glm::dvec3(0.7171, -0.6024, 0.3507))};
  int votes = 0;
  for (const glm::dvec3& d : dirs) {
    int hits = 0;
    for_each_triangle(m, [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
      glm::dvec3 e1 = b - a, e2 = c - a, h = glm::cross(d, e2);
      double det = glm::dot(e1, h);
      if (std::abs(det) < 1e-18) return;
      glm::dvec3 s = p - a;
      double u = glm::dot(s, h) / det;
      if (u < 0.0 || u > 1.0) return;
      glm::dvec3 q = glm::cross(s, e1);
      double v = glm::dot(d, q) / det;
      if (v < 0.0 || u + v > 1.0) return;
      if (glm::dot(e2, q) / det > 0.0) ++hits;
    });
    votes += hits & 1;
  }
  return votes >= 2;
}

double brute_distance(const Mesh& m, glm::vec3 p) {
  double best = 1e30;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    glm::vec3 q = closest_on_triangle(p, m.vertices[m.indices[t]].position, m.vertices[m.indices[t + 1]].position,
                                      m.vertices[m.indices[t + 2]].position);
    best = std::min(best, double(glm::length(q - p)));
  }
  return best;
}

}  // namespace

TEST(Hull, FieldMatchesFormulaByBruteForce) {
  Rng rng(11, 1);
  std::vector<glm::vec3> centers;
  for (int i = 0; i < 600; ++i)
    centers.push_back(glm::vec3(rng.uniform(-1, 1), rng.uniform(0, 2), rng.uniform(-1, 1)));
  const float r = 0.2f;
  MetaballField field = make_metaball_field(centers, r);
  double max_value_err = 0.0, max_grad_err = 0.0;
  int nonzero = 0;
  for (int k = 0; k < 400; ++k) {
    glm::vec3 q(rng.uniform(-1.3, 1.3), rng.uniform(-0.3, 2.3), rng.uniform(-1.3, 1.3));
    double f = 0.0;
    glm::dvec3 g(0.0);
    for (const glm::vec3& p : centers) {
      glm::dvec3 d = glm::dvec3(q) - glm::dvec3(p);
      double x = 1.0 - glm::dot(d, d) / (double(r) * r);
      if (x > 0.0) f += x * x, g += -4.0 * x / (double(r) * r) * d;
    }
    nonzero += f > 0.0;
    max_value_err = std::max(max_value_err, std::abs(double(field_value(field, q)) - f) / std::max(1.0, f));
    max_grad_err = std::max(max_grad_err, glm::length(glm::dvec3(field_gradient(field, q)) - g) /
                                              std::max(1.0, glm::length(g)));
  }
  EXPECT_GT(nonzero, 100);  // the points actually probe the field
  EXPECT_LT(max_value_err, 1e-5);
  EXPECT_LT(max_grad_err, 1e-4);

  // The scattered grid agrees with the point queries.
  ScalarGrid grid = sample_field(field, 0.07f);
  for (int k = 0; k < 300; ++k) {
    int i = int(rng.uniform() * grid.size.x), j = int(rng.uniform() * grid.size.y), l = int(rng.uniform() * grid.size.z);
    EXPECT_NEAR(grid.at(i, j, l), field_value(field, grid.point(i, j, l)), 1e-4);
  }
  // Border samples are zero (the precondition for a closed surface).
  for (int j = 0; j < grid.size.y; ++j)
    for (int i = 0; i < grid.size.x; ++i) EXPECT_EQ(grid.at(i, j, 0), 0.0f);
}

TEST(Hull, MarchingCubesSphereIsClosedOutwardAndAccurate) {
  ScalarGrid g;
  g.size = glm::ivec3(34);
  g.spacing = 0.1f;
  g.origin = glm::vec3(-1.65f);
  g.values.resize(size_t(34) * 34 * 34);
  for (int k = 0; k < 34; ++k)
    for (int j = 0; j < 34; ++j)
      for (int i = 0; i < 34; ++i) g.values[g.index(i, j, k)] = 1.2f - glm::length(g.point(i, j, k));
  Mesh m = marching_cubes(g, 0.0f);
  expect_closed_oriented(m);
  const double exact = 4.0 / 3.0 * M_PI * 1.2 * 1.2 * 1.2;
  EXPECT_NEAR(signed_volume(m), exact, 0.02 * exact);  // positive: counter-clockwise outside
  for (const Vertex& v : m.vertices) EXPECT_NEAR(glm::length(v.position), 1.2f, 0.01f);
  // Every face normal points away from the centre.
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    glm::vec3 a = m.vertices[m.indices[t]].position, b = m.vertices[m.indices[t + 1]].position,
              c = m.vertices[m.indices[t + 2]].position;
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), a + b + c), 0.0f);
  }
}

TEST(Hull, MarchingCubesNoiseWithSaddlesIsClosed) {
  // Random values make every ambiguous face and cell configuration occur: the face decision
  // must agree between neighbouring cells, or edges end up used once.
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    ScalarGrid g;
    g.size = glm::ivec3(14, 12, 13);
    g.values.resize(size_t(14) * 12 * 13);
    Rng rng(seed, 3);
    for (int k = 0; k < g.size.z; ++k)
      for (int j = 0; j < g.size.y; ++j)
        for (int i = 0; i < g.size.x; ++i) {
          bool border = i == 0 || j == 0 || k == 0 || i == g.size.x - 1 || j == g.size.y - 1 || k == g.size.z - 1;
          g.values[g.index(i, j, k)] = border ? -1.0f : float(rng.symmetric());
        }
    Mesh m = marching_cubes(g, 0.0f);
    expect_closed_oriented(m);
    // Outward overall: the enclosed volume is positive and about the fraction inside.
    EXPECT_GT(signed_volume(m), 0.0);
  }
}

TEST(Hull, CrownHullIsClosedOutwardAndContainsEveryLeaf) {
  std::vector<LeafPlacement> leaves = crown(3000, 5);
  HullParams params;
  Hull hull = build_hull(leaves, 4.0f, params);
  EXPECT_FLOAT_EQ(hull.radius, 0.2f);
  EXPECT_FLOAT_EQ(hull.iso, params.iso);
  expect_closed_oriented(hull.mesh);
  EXPECT_GT(signed_volume(hull.mesh), 0.0);

  // Vertex normals (-grad F) agree with the triangles' winding.
  size_t disagree = 0;
  for (size_t t = 0; t < hull.mesh.indices.size(); t += 3) {
    const Vertex &a = hull.mesh.vertices[hull.mesh.indices[t]], &b = hull.mesh.vertices[hull.mesh.indices[t + 1]],
                 &c = hull.mesh.vertices[hull.mesh.indices[t + 2]];
    glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
    if (glm::dot(face, a.normal + b.normal + c.normal) <= 0.0f) ++disagree;
  }
  EXPECT_LE(double(disagree), 0.002 * double(hull.mesh.indices.size() / 3));
  for (const Vertex& v : hull.mesh.vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);

  // F(centre) >= 1 > iso for every leaf, and every centre is inside the extracted mesh.
  MetaballField field = make_metaball_field([&] {
    std::vector<glm::vec3> c;
    for (const LeafPlacement& l : leaves) c.push_back(leaf_center(l));
    return c;
  }(), hull.radius);
  size_t outside = 0;
  for (size_t i = 0; i < leaves.size(); i += 7) {  // every 7th: ray casting is brute force
    glm::vec3 c = leaf_center(leaves[i]);
    ASSERT_GE(field_value(field, c), hull.iso);
    outside += !inside_mesh(hull.mesh, glm::dvec3(c));
  }
  for (size_t i = 3000; i < 3005; ++i) outside += !inside_mesh(hull.mesh, glm::dvec3(leaf_center(leaves[i])));
  EXPECT_EQ(outside, 0u);
  // And the hull is tight: points a little more than r away from every leaf are outside.
  EXPECT_FALSE(inside_mesh(hull.mesh, glm::dvec3(0.0, 3.0 + 1.2 + 1.6 * hull.radius, 0.0)));
  EXPECT_FALSE(inside_mesh(hull.mesh, glm::dvec3(2.5 + 0.3, 1.15, -1.0)));  // between isolated leaves
}

TEST(Hull, SamplesLieOnTheSurfaceAndAreSpread) {
  Hull hull = build_hull(crown(2000, 9), 4.0f);
  ASSERT_EQ(hull.samples.size(), 64u);
  ASSERT_EQ(hull.sample_normals.size(), 64u);
  const double a = area(hull.mesh);
  const double ideal = std::sqrt(a / 64.0);
  double min_pair = 1e30;
  for (size_t i = 0; i < hull.samples.size(); ++i) {
    EXPECT_LT(brute_distance(hull.mesh, hull.samples[i]), 1e-4);
    EXPECT_NEAR(glm::length(hull.sample_normals[i]), 1.0f, 1e-4f);
    for (size_t j = 0; j < i; ++j) min_pair = std::min(min_pair, double(glm::length(hull.samples[i] - hull.samples[j])));
  }
  // Uniform random points would have a minimum spacing near ideal / 8; farthest-point
  // selection keeps it around half the ideal spacing.
  EXPECT_GT(min_pair, 0.3 * ideal) << "area " << a;
  // Normals point outward: a step along them leaves the field's iso-region.
  std::vector<glm::vec3> c;
  for (const LeafPlacement& l : crown(2000, 9)) c.push_back(leaf_center(l));
  MetaballField field = make_metaball_field(c, hull.radius);
  for (size_t i = 0; i < hull.samples.size(); ++i)
    EXPECT_LT(field_value(field, hull.samples[i] + 0.1f * hull.radius * hull.sample_normals[i]),
              field_value(field, hull.samples[i] - 0.1f * hull.radius * hull.sample_normals[i]));
}

TEST(Hull, DeterministicAndSeeded) {
  std::vector<LeafPlacement> leaves = crown(1500, 2);
  Hull a = build_hull(leaves, 4.0f), b = build_hull(leaves, 4.0f);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  EXPECT_EQ(a.mesh.indices, b.mesh.indices);
  for (size_t i = 0; i < a.mesh.vertices.size(); ++i) {
    EXPECT_EQ(a.mesh.vertices[i].position, b.mesh.vertices[i].position);
    EXPECT_EQ(a.mesh.vertices[i].normal, b.mesh.vertices[i].normal);
  }
  EXPECT_EQ(a.samples, b.samples);
  HullParams other;
  other.seed = 2;
  EXPECT_NE(build_hull(leaves, 4.0f, other).samples, a.samples);
}

TEST(Hull, BadInputIsInputError) {
  std::vector<LeafPlacement> leaves = crown(50, 1);
  EXPECT_THROW(build_hull(leaves, 0.0f), InputError);
  EXPECT_THROW(build_hull(leaves, std::nanf("")), InputError);
  EXPECT_THROW(build_hull(leaves, INFINITY), InputError);
  HullParams p;
  p.iso = 1.5f;
  EXPECT_THROW(build_hull(leaves, 4.0f, p), InputError);
  p = {};
  p.radius_fraction = -0.1f;
  EXPECT_THROW(build_hull(leaves, 4.0f, p), InputError);
  leaves[3].position.x = std::nanf("");
  EXPECT_THROW(build_hull(leaves, 4.0f), InputError);
  // Absurd spread (one leaf a kilometre away): refused, not a gigabyte grid or a lost hull.
  leaves[3].position = glm::vec3(1000.0f, 0.0f, 0.0f);
  EXPECT_THROW(build_hull(leaves, 4.0f), InputError);
  // Moderately wide (a 12 m bush of height 1): coarser grid, still closed, still whole.
  leaves[3].position = glm::vec3(12.0f, 0.0f, 0.0f);
  Hull wide = build_hull(leaves, 1.0f);
  expect_closed_oriented(wide.mesh);
  // No leaves: an empty hull, not an error.
  Hull empty = build_hull({}, 4.0f);
  EXPECT_TRUE(empty.mesh.indices.empty());
  EXPECT_TRUE(empty.samples.empty());
}

TEST(Hull, AttachStoresMeshAndSamples) {
  TreeModel model;
  model.leaves = crown(800, 4);
  EXPECT_GT(plant_height(model), 2.0f);
  Hull hull = build_hull(model.leaves, plant_height(model));
  attach_hull(model, hull);
  EXPECT_EQ(model.hull.indices, hull.mesh.indices);
  ASSERT_TRUE(model.bake.hull.has_value());
  EXPECT_EQ(model.bake.hull->points, hull.samples);
  EXPECT_EQ(model.bake.hull->normals, hull.sample_normals);
  EXPECT_EQ(model.bake.hull->iso, hull.iso);
  EXPECT_EQ(model.bake.hull->radius, hull.radius);
  EXPECT_FALSE(model.bake.baked()) << "a hull alone is not a bake";
}

TEST(Hull, NearestOnMeshMatchesBruteForce) {
  Hull hull = build_hull(crown(1000, 3), 4.0f);
  MeshNearest index = make_mesh_nearest(hull.mesh);
  Rng rng(4, 4);
  for (int k = 0; k < 200; ++k) {
    glm::vec3 q(rng.uniform(-3, 3.5), rng.uniform(-0.5, 5), rng.uniform(-2, 2));
    NearestHit hit = nearest_on_mesh(index, q);
    EXPECT_NEAR(hit.distance, brute_distance(hull.mesh, q), 1e-5);
    EXPECT_NEAR(glm::length(hit.normal), 1.0f, 1e-4f);
  }
}
