#include "generators/tree/foliage.h"

#include <algorithm>
#include <cmath>

#include "generators/core/rng.h"
#include "generators/core/toml_reader.h"
#include "generators/mesh/frames.h"

namespace forest {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kGoldenAngle = 2.399963229728653;  // 137.5°: the spiral of shoots on a branch
}  // namespace

FoliageKeys read_foliage_keys(const TomlTable& t, LeafShape leaf_shape) {
  const FoliageKeys d;
  FoliageKeys k;
  std::string mode = t.choice("foliage", "shoots", {"shoots", "leaves"});
  k.shoot.single_leaf = mode == "leaves";
  k.shoot.leaf_shape = leaf_shape;
  // Botanical sizes: a blade of 1 cm (small needles' shoot) to 0.5 m (large leaves).
  k.leaf_size = float(t.number("leaf_size", d.leaf_size, 0.0, 0.5));
  k.enabled = k.leaf_size > 0.0f;
  k.size_jitter = float(t.number("leaf_size_jitter", d.size_jitter, 0.0, 0.9));
  k.shoot.phyllotaxis = *parse_phyllotaxis(t.choice(
      "leaf_phyllotaxis", phyllotaxis_name(d.shoot.phyllotaxis), {"alternate", "distichous", "opposite",
                                                                  "decussate", "whorled", "spiral"}));
  k.shoot.leaves = int(t.integer("leaves_per_shoot", d.shoot.leaves, 4, 24));
  k.shoot_length = float(t.number("shoot_length", d.shoot_length, 0.03, 1.5));
  k.shoot.leaf_angle_deg = float(t.number("leaf_angle", d.shoot.leaf_angle_deg, 5.0, 90.0));
  if (!k.shoot.single_leaf) {
    if (k.enabled && k.leaf_size > 0.9f * k.shoot_length)
      t.fail("leaf_size", "must be at most 0.9 shoot_length (a shoot carries several leaves)");
    k.shoot.leaf_length = k.enabled ? k.leaf_size / k.shoot_length : 0.3f;
  }
  k.spacing = float(t.number("shoot_spacing", d.spacing, 0.01, 10.0));
  k.depth = float(t.number("foliage_depth", d.depth, 0.0, 100.0));
  k.angle_deg = float(t.number("shoot_angle", d.angle_deg, 0.0, 180.0));
  k.angle_jitter_deg = float(t.number("shoot_angle_jitter", d.angle_jitter_deg, 0.0, 90.0));
  k.per_tip = int(t.integer("shoots_per_tip", d.per_tip, 0, 16));
  k.per_spray = int(t.integer("shoots_per_spray", d.per_spray, 1, 8));
  k.color_jitter = float(t.number("leaf_color_jitter", d.color_jitter, 0.0, 0.5));
  k.season = t.choice("season", "summer", {"summer", "autumn"}) == "autumn" ? Season::autumn : Season::summer;
  k.autumn_color = t.vec3("autumn_color", d.autumn_color, 0.0, 1.0);
  k.evergreen = t.boolean("evergreen", d.evergreen);
  return k;
}

glm::vec3 season_leaf_color(const FoliageKeys& k, glm::vec3 summer) {
  return k.season == Season::autumn && !k.evergreen ? k.autumn_color : summer;
}

std::vector<float> length_to_farthest_tip(const TreeGraph& graph) {
  std::vector<float> s(graph.nodes.size(), 0.0f);
  for (size_t i = graph.nodes.size(); i-- > 1;) {  // children after parents
    int p = graph.nodes[i].parent;
    if (p < 0) continue;
    float len = glm::length(graph.nodes[i].position - graph.nodes[size_t(p)].position);
    s[size_t(p)] = std::max(s[size_t(p)], s[i] + len);
  }
  return s;
}

namespace {
float element_length(const FoliageKeys& k) { return k.shoot.single_leaf ? k.leaf_size : k.shoot_length; }
float season_jitter(const FoliageKeys& k) {
  return k.season == Season::autumn && !k.evergreen ? 2.0f * k.color_jitter : k.color_jitter;
}
}  // namespace

void size_foliage(TreeGraph& graph, const FoliageKeys& k, uint64_t seed) {
  if (!k.enabled) return graph.leaves.clear();
  Rng rng(seed, /*stream=*/3);
  for (LeafPlacement& leaf : graph.leaves) {
    leaf.scale = element_length(k) * float(1.0 + double(k.size_jitter) * rng.symmetric());
    leaf.color = leaf_color_variation(rng, season_jitter(k));
  }
}

void place_foliage(TreeGraph& graph, const FoliageKeys& k, uint64_t seed) {
  graph.leaves.clear();
  const size_t n = graph.nodes.size();
  if (!k.enabled || n < 2) return;
  const std::vector<float> s = length_to_farthest_tip(graph);
  const auto children = children_of(graph);
  const float element = element_length(k);

  // The point inside the crown that blades face away from: the centroid of the young wood's
  // nodes, lowered by a quarter of their height range (light comes from above and outside).
  glm::vec3 centroid(0.0f);
  float lo = INFINITY, hi = -INFINITY;
  size_t count = 0;
  for (size_t i = 1; i < n; ++i)
    if (s[i] <= k.depth) {
      centroid += graph.nodes[i].position;
      lo = std::min(lo, graph.nodes[i].position.y), hi = std::max(hi, graph.nodes[i].position.y);
      ++count;
    }
  if (count == 0) return;
  centroid /= float(count);
  const glm::vec3 inside = centroid - glm::vec3(0.0f, 0.25f * (hi - lo), 0.0f);

  Rng rng(seed, /*stream=*/3);
  const float tilt0 = k.angle_deg * float(kPi) / 180.0f;
  const float tilt_jitter = k.angle_jitter_deg * float(kPi) / 180.0f;
  const float jitter = season_jitter(k);
  auto add = [&](glm::vec3 pos, glm::vec3 axis, glm::vec3 reference, double azimuth) {
    float tilt = tilt0 + tilt_jitter * float(rng.symmetric());
    for (int m = 0; m < k.per_spray; ++m) {
      float size = element * float(1.0 + double(k.size_jitter) * rng.symmetric());
      glm::vec3 facing = pos - inside;
      facing = glm::length(facing) > 1e-6f ? glm::normalize(facing) : glm::vec3(0, 1, 0);
      // Shoots turn their upper side to the light: outward and up.
      facing = glm::normalize(facing + glm::vec3(0.0f, 0.15f, 0.0f));
      LeafPlacement leaf = orient_leaf(pos, axis, float(azimuth), tilt, facing, size, reference);
      leaf.color = leaf_color_variation(rng, jitter);
      graph.leaves.push_back(leaf);
      // The next shoot of the spray grows from this one's end, turned to alternate sides in
      // the shoot's plane (a twig system ramifies sympodially, in a zigzag) and bent a little
      // toward the horizontal.
      glm::vec3 dir = leaf.rotation * glm::vec3(0.0f, 1.0f, 0.0f);
      const glm::vec3 side = leaf.rotation * glm::vec3(1.0f, 0.0f, 0.0f);
      pos += dir * (0.8f * size);
      const float turn = (m % 2 ? -1.0f : 1.0f) * (0.45f + 0.25f * float(rng.uniform()));
      dir = glm::normalize(dir * std::cos(turn) + side * std::sin(turn));
      glm::vec3 flat(dir.x, 0.0f, dir.z);
      if (glm::length(flat) > 1e-4f) dir = glm::normalize(dir + 0.2f * (glm::normalize(flat) - dir));
      reference = any_perpendicular(dir);
      axis = dir;
      tilt = 0.0f;
      azimuth = 0.0;
    }
  };

  // Per node: the reference direction transported along its branch and the spiral phase, so
  // that successive elements of one branch keep turning by the golden angle.
  std::vector<glm::vec3> axis_of(n, glm::vec3(0.0f, 1.0f, 0.0f)), ref_of(n, glm::vec3(1.0f, 0.0f, 0.0f));
  std::vector<double> phase_of(n, 0.0);
  for (size_t i = 1; i < n; ++i) {
    const TreeNode& node = graph.nodes[i];
    const size_t parent = size_t(node.parent);
    const glm::vec3 from = graph.nodes[parent].position;
    const glm::vec3 seg = node.position - from;
    const float len = glm::length(seg);
    const glm::vec3 axis = len > 1e-9f ? seg / len : axis_of[parent];
    const bool continues = children[parent].size() == 1 && parent > 0;
    ref_of[i] = continues ? transport(ref_of[parent], axis_of[parent], axis) : any_perpendicular(axis);
    phase_of[i] = continues ? phase_of[parent] : rng.uniform(0.0, 2.0 * kPi);
    axis_of[i] = axis;
    // The part of this segment within `depth` of its farthest tip bears foliage: the points
    // at distance t ∈ [0, bearing] back from the node.
    const float bearing = std::min(len, k.depth - s[i]);
    if (bearing > 0.0f) {
      double offset = rng.uniform() * double(k.spacing);
      for (double t = offset; t < double(bearing); t += double(k.spacing)) {
        glm::vec3 pos = node.position - axis * float(t);
        phase_of[i] += kGoldenAngle;
        add(pos, axis, ref_of[i], phase_of[i]);
      }
    }
    if (children[i].empty()) {
      // The tip: shoots spread evenly around the branch's end, from a random start.
      double start = rng.uniform(0.0, 2.0 * kPi);
      for (int m = 0; m < k.per_tip; ++m)
        add(node.position, axis, ref_of[i], start + 2.0 * kPi * double(m) / double(k.per_tip));
    }
  }
  // Sprays of low, arching branches can bend down to the ground; none reaches below
  // kFoliageGroundClearance above the root (the ground is there), neither base nor tip.
  const float ground = graph.nodes[0].position.y + kFoliageGroundClearance;
  std::erase_if(graph.leaves, [&](const LeafPlacement& l) {
    glm::vec3 tip = l.position + l.rotation * glm::vec3(0.0f, l.scale, 0.0f);
    return std::min(l.position.y, tip.y) < ground;
  });
}

}  // namespace forest
