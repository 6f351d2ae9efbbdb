// Method `sketch-mrf`, part 2: the database of tree templates (Neubert 2012 ch4.8) and template
// choice by L = L_c + L_b (eqs. 4.26, 4.27).
//
// The database holds a few trees generated with the L-system generator (generators/tree/
// lsystem.h) after the presets in scenes/species/ (broadleaf, conifer, fig2_1) plus a
// spreading umbrella form, kept as skeleton statistics: the branching skeleton (branch
// points and tips), its 3D Omega (the prior of the factor graph), and per view (8 azimuths)
// the crown footprint and the 2D branching statistics. The database is built once per
// process (deterministic, ~0.1 s).
#pragma once
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/sketch_mrf/sketch_mrf_inference.h"
#include "generators/methods/common/strokes_io.h"

namespace forest {

inline constexpr int kFootprintDirections = 32;  // K_f
inline constexpr int kTemplateViews = 8;

// Mean and standard deviation of the 2D length ratio s, apical angle alpha and lateral
// angle beta over parent/child pairs of a drawing (apical = smallest 2D angle).
struct BranchStats2D {
  double mu[3] = {0, 0, 0};
  double sd[3] = {1, 1, 1};
};

struct TemplateView {
  std::vector<double> footprint;  // K_f radial distances of the normalized convex hull
  BranchStats2D stats;
};

struct SketchTemplate {
  std::string name;
  std::vector<glm::dvec3> nodes;  // branching skeleton, node 0 the root; parent < index
  std::vector<int> parent;
  Omega omega;                    // 3D statistics: the factor graph's prior
  std::vector<TemplateView> views;
  float leaf_size = 0.2f;         // the template's leaf model
  int leaves_per_tip = 3;
};

const std::vector<SketchTemplate>& sketch_template_database();
// Index by name, or -1.
int find_sketch_template(const std::string& name);

// Footprint descriptor (Lamdan 1988 as used in 4.8): convex hull of the points, scaled so
// max(w, h) = 1, radial distances from the bounding-box centre in K_f directions.
std::vector<double> footprint_descriptor(const std::vector<glm::dvec2>& points);
BranchStats2D branch_stats_2d(const std::vector<glm::dvec2>& xy, const std::vector<int>& parent);

struct TemplateChoice {
  int index = -1;
  int view = 0;
  double score = -1e300;  // L(S, E | v)
  std::vector<double> best_per_template;
};
// argmax over templates and views of L_c + L_b (L_b alone when the sketch has no crown).
TemplateChoice choose_template(const SketchTree& sketch);

// A sketch of a template seen from view `view` (rotation of 2 pi view / 8 about +y):
// strokes follow the apical children, laterals up to `generations` - 1 branchings start new
// strokes; every point keeps its ground-truth depth; the crown curve is the convex hull of
// the whole projected tree.
Drawing project_template(const SketchTemplate& t, int view, int generations, bool with_crown);

}  // namespace forest
