#include "engine/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include <glm/gtc/constants.hpp>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/limits.h"
#include "generators/core/rng.h"
#include "generators/species/registry.h"

namespace forest {

namespace {

uint32_t pack_tint(Rng& rng) {
  // Per-tree color variation around 1.0 (128 = no change), decoded in the shaders.
  auto c = [&](double spread) { return uint32_t(std::lround(128.0 + rng.uniform(-spread, spread))); };
  uint32_t brightness = c(28.0);
  return c(18.0) | (c(10.0) << 8) | (c(18.0) << 16) | (brightness << 24);
}

gpu::Instance make_instance(glm::vec3 position, float scale, float yaw_rad, uint32_t model, uint32_t tint) {
  gpu::Instance inst{};
  inst.position_scale = glm::vec4(position, scale);
  inst.yaw_cos_sin = glm::vec2(std::cos(yaw_rad), std::sin(yaw_rad));
  inst.model = model;
  inst.tint = tint;
  return inst;
}

// Uniform grid of accepted trunk positions for the minimum-spacing test.
struct SpacingGrid {
  float cell;
  std::unordered_map<uint64_t, std::vector<glm::vec2>> cells;
  static uint64_t key(int64_t x, int64_t z) { return (uint64_t(x) << 32) ^ uint64_t(uint32_t(z)); }
  bool free(glm::vec2 p, float spacing) const {
    if (spacing <= 0.0f) return true;
    int64_t cx = int64_t(std::floor(p.x / cell)), cz = int64_t(std::floor(p.y / cell));
    for (int64_t dz = -1; dz <= 1; ++dz)
      for (int64_t dx = -1; dx <= 1; ++dx) {
        auto it = cells.find(key(cx + dx, cz + dz));
        if (it == cells.end()) continue;
        for (glm::vec2 q : it->second)
          if (glm::dot(p - q, p - q) < spacing * spacing) return false;
      }
    return true;
  }
  void add(glm::vec2 p) {
    cells[key(int64_t(std::floor(p.x / cell)), int64_t(std::floor(p.y / cell)))].push_back(p);
  }
};

glm::vec2 uniform_in_disc(Rng& rng, glm::vec2 center, float radius) {
  double r = radius * std::sqrt(rng.uniform()), phi = rng.uniform(0.0, 2.0 * glm::pi<double>());
  return center + glm::vec2(float(r * std::cos(phi)), float(r * std::sin(phi)));
}

// Two independent standard normal numbers (Box-Muller).
glm::vec2 gaussian2(Rng& rng) {
  double r = std::sqrt(-2.0 * std::log(1.0 - rng.uniform())), phi = rng.uniform(0.0, 2.0 * glm::pi<double>());
  return {float(r * std::cos(phi)), float(r * std::sin(phi))};
}

}  // namespace

std::vector<gpu::Instance> place_trees(const SceneDesc& desc, const Terrain& terrain, uint32_t* shortfall) {
  std::vector<gpu::Instance> out;
  const PlacementDesc& p = desc.placement;
  SpacingGrid grid{std::max(p.min_spacing, 1.0f), {}};
  Rng rng(p.seed, 0x7233e5);  // stream: placement
  float half = 0.5f * terrain.desc.size;

  for (const TreeDesc& t : desc.trees) {
    glm::vec3 pos(t.x, terrain.height_at(t.x, t.z), t.z);
    out.push_back(make_instance(pos, t.scale, glm::radians(t.yaw_deg), t.species, pack_tint(rng)));
    grid.add({t.x, t.z});
  }

  std::vector<double> cumulative;
  double total = 0.0;
  for (const SpeciesDesc& s : desc.species) cumulative.push_back(total += s.weight);

  // Thomas cluster process: parents uniform in the disc; each candidate is a Gaussian offset
  // from a random parent. Its own stream, so uniform scenes keep their placements.
  Rng cluster_rng(p.seed, 0xc1a5732);
  std::vector<glm::vec2> parents(p.clusters);
  for (glm::vec2& c : parents) c = uniform_in_disc(cluster_rng, p.center, p.radius);

  float min_normal_y = std::cos(glm::radians(p.max_slope_deg));
  uint64_t attempts = uint64_t(p.count) * 30, placed = 0;
  for (uint64_t a = 0; a < attempts && placed < p.count; ++a) {
    // Uniform in the disc (or around a cluster parent), clipped to the terrain.
    glm::vec2 xz = uniform_in_disc(rng, p.center, p.radius);
    if (!parents.empty()) {
      glm::vec2 parent = parents[std::min(size_t(cluster_rng.uniform() * double(parents.size())), parents.size() - 1)];
      xz = parent + p.cluster_radius * gaussian2(cluster_rng);
    }
    double pick = rng.uniform(0.0, total);
    float scale = float(rng.uniform(p.scale_min, p.scale_max));
    float yaw = float(rng.uniform(0.0, 2.0 * glm::pi<double>()));
    uint32_t tint = pack_tint(rng);
    if (std::abs(xz.x) > half || std::abs(xz.y) > half) continue;
    if (!parents.empty() && glm::distance(xz, p.center) > p.radius) continue;  // a cluster's tail outside the region
    if (terrain.normal_at(xz.x, xz.y).y < min_normal_y) continue;
    if (!grid.free(xz, p.min_spacing)) continue;
    uint32_t species = uint32_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
    species = std::min(species, uint32_t(desc.species.size() - 1));
    // Sink the base a little so trunks on slopes do not float.
    glm::vec3 pos(xz.x, terrain.height_at(xz.x, xz.y) - 0.05f * scale, xz.y);
    out.push_back(make_instance(pos, scale, yaw, species, tint));
    grid.add(xz);
    ++placed;
  }
  if (shortfall) *shortfall = uint32_t(p.count - placed);
  return out;
}

Scene build_scene(const SceneDesc& desc, const SceneBuildOptions& options) {
  Scene scene;
  scene.desc = desc;
  scene.terrain = make_terrain(desc.terrain);
  for (const SpeciesDesc& s : desc.species) {
    if (!s.model.empty()) {
      scene.models.push_back(load_glb(s.model));
    } else if (options.species) {
      scene.models.push_back(options.species(s, desc.bake));
    } else {
      GenerateOptions generate;
      generate.seed = s.seed;
      scene.models.push_back(generate_from_species(s.preset, generate));
    }
  }
  // Every model's leaves share one GPU buffer: bound its size (generators/core/limits.h).
  size_t leaves = 0;
  for (const TreeModel& m : scene.models) leaves += m.leaves.size();
  if (leaves > kMaxSceneLeaves)
    throw InputError(desc.file.string(), 0, "species",
                     "the models have " + std::to_string(leaves) + " leaves together, more than the limit of " +
                         std::to_string(kMaxSceneLeaves));
  scene.instances = place_trees(desc, scene.terrain, &scene.placement_shortfall);
  return scene;
}

}  // namespace forest

namespace forest {

FullDetailSize full_detail_size(const Scene& scene) {
  std::vector<FullDetailSize> per_model;
  for (const TreeModel& m : scene.models)
    per_model.push_back({uint64_t(m.branches.vertices.size()) + uint64_t(m.leaves.size()) * m.leaf_card.vertices.size(),
                         uint64_t(m.branches.indices.size() / 3) + uint64_t(m.leaves.size()) * (m.leaf_card.indices.size() / 3)});
  FullDetailSize total;
  for (const gpu::Instance& inst : scene.instances) {
    total.vertices += per_model[inst.model].vertices;
    total.triangles += per_model[inst.model].triangles;
  }
  return total;
}

}  // namespace forest
