// Method `silhouettes` (Wither 2009): a trunk axis stroke and
// a crown silhouette (level 0; optional level-1 over-sketched branches and sub-silhouettes,
// and a leaf silhouette) -> branches into the silhouette's bumps (skeleton terminals, BAF,
// Hermite curves) -> inferred sub-silhouettes -> fill-in -> the same, recursively, inside
// every sub-silhouette -> 3D: azimuths by the depletion-replacement optimizer with a
// phyllotaxis preset, extra branches grown to the crown's surface of revolution -> mesh.
#pragma once
#include <filesystem>
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"
#include "generators/methods/silhouettes/silhouettes_branches.h"
#include "generators/methods/common/strokes_io.h"

namespace forest {

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kSilhouettesMethod;

// The synthetic drawings: "round" (the reference note's trunk (0,0)-(0,8), ellipse centre
// (0, 6) radii 3 x 2.5 with 5 discs at 20, 60, 90, 120, 160 degrees, one scripted level-1
// over-sketch, leaf 0.3 x 0.1) and "poplar" (a tall narrow crown with 7 bumps).
Drawing silhouettes_synthetic_drawing(const std::string& name);
// Centres and radii of the round drawing's discs (for tests).
std::vector<std::pair<glm::dvec2, double>> silhouettes_round_discs();

// The 2D hierarchy (levels of branches inside their silhouettes) before 3D placement.
struct SilhouetteNode {
  Branch2D branch;       // node 0: the trunk (curve = axis stroke, crown = silhouette)
  int parent = -1;
  int level = 0;
  std::vector<int> children;
};
struct SilhouetteParams {
  double bottom_angle = 80.0, top_angle = 30.0;  // BAF, degrees
  int levels = 3;                                // branch levels below the trunk
  double max_overlap = 0.2;                      // fill-in
  int fill_samples = 8;                          // fill-in positions per side
  size_t max_branches = 4000;
};
std::vector<SilhouetteNode> infer_hierarchy(const Drawing& drawing, const SilhouetteParams& params);

}  // namespace forest
