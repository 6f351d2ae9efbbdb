#include "engine/tools/gallery/human_figure.h"

#include <algorithm>

#include "generators/mesh/mesher.h"

namespace forest {

TreeModel human_figure(float height) {
  const float s = height / 1.8f;
  TreeGraph g;
  auto add = [&](glm::vec3 p, float radius, int parent) {
    g.nodes.push_back(TreeNode{p * s, radius * s, parent, 0});
    return int(g.nodes.size() - 1);
  };
  // Proportions of an adult (about 7.5 heads tall): hips at 0.53 H, shoulders at 0.82 H.
  const int pelvis = add({0.0f, 0.95f, 0.0f}, 0.15f, -1);
  for (float side : {-1.0f, 1.0f}) {
    int hip = add({0.10f * side, 0.90f, 0.0f}, 0.075f, pelvis);
    int knee = add({0.11f * side, 0.50f, 0.01f}, 0.055f, hip);
    add({0.12f * side, 0.04f, 0.03f}, 0.045f, knee);
  }
  const int chest = add({0.0f, 1.30f, 0.0f}, 0.17f, pelvis);
  const int neck = add({0.0f, 1.50f, 0.0f}, 0.06f, chest);
  add({0.0f, 1.80f - 0.11f, 0.01f}, 0.10f, neck);  // the head's top at H (a sphere-ish end)
  for (float side : {-1.0f, 1.0f}) {
    int shoulder = add({0.20f * side, 1.46f, 0.0f}, 0.05f, chest);
    int elbow = add({0.25f * side, 1.16f, 0.02f}, 0.04f, shoulder);
    add({0.27f * side, 0.86f, 0.04f}, 0.035f, elbow);
  }
  MesherParams params;
  params.min_sides = params.max_sides = 10;
  TreeModel m;
  m.branches = mesh_branches(g, params);
  m.bark_color = glm::vec3(0.05f, 0.05f, 0.06f);
  m.leaf_card = make_leaf_card();
  m.bounding_sphere = bounding_sphere(m.branches, m.leaf_card, m.leaves);
  m.meta["height"] = height;
  return m;
}

}  // namespace forest
