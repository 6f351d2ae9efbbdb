// Bark uv (generators/mesh/mesher.h): physical, so the bark texture has the same texel
// density on every branch, along tapering tubes, across forks and on the junction surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "generators/mesh/bark_texture.h"
#include "generators/mesh/mesher.h"
#include "generators/species/registry.h"
#include "generators/tree/pipe_model.h"
#include "generators/methods/lsystem/lsystem.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

// The stretch of one triangle's uv map: the singular values of the 2 × 2 Jacobian from its
// plane (metres) to uv (tiles), times the tile size: both 1 where the texture has its
// physical size in every direction. Nullopt for a degenerate triangle.
struct Stretch {
  double lo = 0.0, hi = 0.0;
};
std::optional<Stretch> stretch(const Vertex& a, const Vertex& b, const Vertex& c, double tile) {
  const glm::dvec3 e1 = glm::dvec3(b.position - a.position), e2 = glm::dvec3(c.position - a.position);
  const double l1 = glm::length(e1);
  const glm::dvec3 n = glm::cross(e1, e2);
  if (!(l1 > 0.0) || !(glm::length(n) > 1e-12 * l1 * l1)) return std::nullopt;
  // The triangle in its own plane: x along e1.
  const glm::dvec3 x = e1 / l1, y = glm::normalize(glm::cross(glm::normalize(n), x));
  const glm::dmat2 p(glm::dvec2(l1, 0.0), glm::dvec2(glm::dot(e2, x), glm::dot(e2, y)));
  const glm::dmat2 q(glm::dvec2(b.uv - a.uv), glm::dvec2(c.uv - a.uv));
  const glm::dmat2 j = q * glm::inverse(p) * tile;
  // Singular values of j from the eigenvalues of jᵀj.
  const glm::dmat2 m = glm::transpose(j) * j;
  const double tr = m[0][0] + m[1][1], det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4.0 - det));
  return Stretch{std::sqrt(std::max(0.0, tr / 2.0 - disc)), std::sqrt(tr / 2.0 + disc)};
}

struct DensityReport {
  size_t triangles = 0;
  double median = 0.0;  // of the triangles' area ratio (uv area · tile² / area)
  double within = 0.0;  // fraction whose area ratio and both stretches are within ±25 % of it
};

DensityReport density(const Mesh& mesh, double tile) {
  std::vector<Stretch> all;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    if (auto s = stretch(mesh.vertices[mesh.indices[t]], mesh.vertices[mesh.indices[t + 1]],
                         mesh.vertices[mesh.indices[t + 2]], tile))
      all.push_back(*s);
  DensityReport r;
  r.triangles = all.size();
  if (all.empty()) return r;
  std::vector<double> area;
  for (const Stretch& s : all) area.push_back(s.lo * s.hi);
  std::nth_element(area.begin(), area.begin() + long(area.size() / 2), area.end());
  r.median = area[area.size() / 2];
  const double linear = std::sqrt(r.median);
  size_t ok = 0;
  for (const Stretch& s : all) {
    const double a = s.lo * s.hi;
    ok += a >= 0.75 * r.median && a <= 1.25 * r.median && s.lo >= 0.75 * linear && s.hi <= 1.25 * linear;
  }
  r.within = double(ok) / double(all.size());
  return r;
}

fs::path species(const char* name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (std::string(name) + ".toml");
}

}  // namespace

TEST(BarkUv, TexelDensityIsEvenOverAWholeTree) {
  // An oak: thick trunk, many forks, thin twigs; every bark triangle counts (tubes, junction
  // surfaces, tip cones, hidden start caps).
  TreeModel m = generate_from_species(species("quercus_robur"));
  ASSERT_GT(m.bark_tile_meters, 0.0f);
  DensityReport r = density(m.branches, m.bark_tile_meters);
  ASSERT_GT(r.triangles, 1000u);
  std::printf("texel density: %zu triangles, median area ratio %.3f, %.1f %% within ±25 %%\n", r.triangles, r.median,
              100.0 * r.within);
  EXPECT_NEAR(r.median, 1.0, 0.1);  // uv in tiles of bark_tile_meters
  EXPECT_GE(r.within, 0.95);
}

TEST(BarkUv, TubesAreMappedToScale) {
  // A tapering, bending L-system tree with pipe radii: uv of the tubes and the junctions
  // at the tile size the parameters ask for.
  LSystem s{"X", {{'X', "F[+X][-X]FX", 1.0}, {'F', "FF", 1.0}}};
  TurtleParams tp;
  tp.angle_deg = 30.0f;
  tp.step = 0.3f;
  TreeGraph g = interpret(rewrite(s, 4, 1), tp, 1);
  assign_pipe_radii(g, 0.01f, 2.3f);
  for (float tile : {0.25f, 1.0f}) {
    MesherParams p;
    p.bark_tile_meters = tile;
    DensityReport r = density(mesh_branches(g, p), tile);
    EXPECT_NEAR(r.median, 1.0, 0.1) << tile;
    EXPECT_GE(r.within, 0.95) << tile;
  }
}
