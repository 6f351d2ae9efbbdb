#include "generators/bake/hull/hull.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "generators/bake/hull/hull_field.h"
#include "generators/bake/hull/hull_samples.h"
#include "generators/bake/hull/marching_cubes.h"
#include "generators/core/input_error.h"

namespace forest {

namespace {

void check_range(const std::string& key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi))
    throw InputError("", 0, key,
                     "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                         std::to_string(v));
}

// Outward normals: -grad F (F grows into the hull). Where the gradient vanishes (a field
// saddle exactly on the surface), fall back to the area-weighted triangle normals.
void set_normals(Mesh& mesh, const MetaballField& field) {
  std::vector<glm::vec3> face_sum(mesh.vertices.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    glm::vec3 n = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                             mesh.vertices[c].position - mesh.vertices[a].position);
    face_sum[a] += n, face_sum[b] += n, face_sum[c] += n;
  }
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    glm::vec3 g = -field_gradient(field, mesh.vertices[i].position);
    float len = glm::length(g);
    if (!(len > 1e-6f / field.radius)) {
      g = face_sum[i];
      len = glm::length(g);
    }
    mesh.vertices[i].normal = len > 0.0f ? g / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }
}

}  // namespace

glm::vec3 leaf_center(const LeafPlacement& leaf) {
  return leaf.position + leaf.rotation * glm::vec3(0.0f, 0.5f * leaf.scale, 0.0f);
}

glm::vec3 leaf_normal(const LeafPlacement& leaf) {
  return glm::normalize(leaf.rotation * glm::vec3(0.0f, 0.0f, 1.0f));
}

float plant_height(const TreeModel& model) {
  float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
  for (const Vertex& v : model.branches.vertices) lo = std::min(lo, v.position.y), hi = std::max(hi, v.position.y);
  for (const LeafPlacement& l : model.leaves) {
    float y = leaf_center(l).y;
    lo = std::min(lo, y), hi = std::max(hi, y);
  }
  return hi >= lo ? hi - lo : 0.0f;
}

Hull build_hull(const std::vector<LeafPlacement>& leaves, float height, const HullParams& params) {
  check_range("radius_fraction", params.radius_fraction, 1e-4, 1.0);
  check_range("iso", params.iso, 1e-6, 0.99);
  check_range("cell_fraction", params.cell_fraction, 0.05, 1.0);
  check_range("max_cells_per_axis", params.max_cells_per_axis, 8, 1024);
  check_range("sample_count", params.sample_count, 0, 65536);
  if (!(height > 0.0f) || !std::isfinite(height))
    throw InputError("", 0, "plant_height", "must be positive and finite, got " + std::to_string(height));

  Hull hull;
  hull.iso = params.iso;
  hull.radius = params.radius_fraction * height;
  if (leaves.empty()) return hull;

  std::vector<glm::vec3> centers;
  centers.reserve(leaves.size());
  for (const LeafPlacement& l : leaves) centers.push_back(leaf_center(l));
  MetaballField field = make_metaball_field(std::move(centers), hull.radius);

  // Spacing h = c r. A leaf centre's cell has corners within (√3/2) h of it, where a lone
  // leaf's own contribution is (1 - 3c²/4)²; keeping that >= a puts every centre inside the
  // extracted mesh: c <= sqrt(4/3 (1 - √a)).
  const double c_inside = std::sqrt(4.0 / 3.0 * (1.0 - std::sqrt(double(params.iso))));
  double spacing = double(hull.radius) * std::min(double(params.cell_fraction), c_inside);
  glm::vec3 lo(field.centers[0]), hi(field.centers[0]);
  for (const glm::vec3& p : field.centers) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) + 2.0 * double(hull.radius);
  // The grid adds 2 margin cells and 1 point: keep points per axis <= max_cells_per_axis.
  // A coarser grid loses the containment guarantee, not closedness; beyond spacing = r a
  // lone leaf's ball could fall between the samples and vanish, so that is an error (a crown
  // that wide compared to its height is a stray leaf, not a plant).
  spacing = std::max(spacing, span / double(params.max_cells_per_axis - 4));
  if (spacing > double(hull.radius))
    throw InputError("", 0, "leaves",
                     "foliage spans " + std::to_string(span) + " m, too wide for a hull of radius " +
                         std::to_string(hull.radius) + " m (plant height " + std::to_string(height) +
                         " m): a stray leaf?");
  ScalarGrid grid = sample_field(field, float(spacing));
  hull.mesh = marching_cubes(grid, params.iso, [&](glm::vec3 q) { return field_value(field, q); });
  set_normals(hull.mesh, field);

  SurfaceSamples s = spread_samples(hull.mesh, params.sample_count, params.seed);
  hull.samples = std::move(s.points);
  hull.sample_normals = std::move(s.normals);
  return hull;
}

void attach_hull(TreeModel& model, const Hull& hull) {
  model.hull = hull.mesh;
  model.bake.hull = HullSamples{hull.samples, hull.sample_normals, hull.iso, hull.radius};
}

}  // namespace forest
