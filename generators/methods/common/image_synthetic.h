// Synthetic image inputs (Neubert 2012 ch3, Shlyakhter 2001 "synthetic input"): a known crown made of
// primitives (ellipsoids, cones, a trunk cylinder) is rendered on the CPU into silhouette masks
// at known camera poses, and a known trunk + first-order branches are projected into each view
// as attractor polylines. Lets the image-based methods run, and be tested, without photos.
//
// Species files select it with a `crown` table instead of a `views` file:
//   crown = { shape = "ellipsoid" | "cone" | "lobes", height = 10.0, width = 7.0, depth = 7.0,
//             trunk_height = 2.5, trunk_radius = 0.3, branches = 5,
//             views = 2, resolution = 128, camera = "orthographic" | "perspective" }
// Orthographic views look horizontally at azimuths 180 deg / views apart (two views: front
// and side, as in Neubert 2012 ch3); perspective views sit on a circle around the tree
// (Shlyakhter 2001: radius ~2 tree heights, looking at mid-height).
#pragma once
#include <string>
#include <vector>

#include "generators/methods/common/image_inputs.h"

namespace forest {

class TomlTable;

struct CrownPrimitive {
  enum class Kind { Ellipsoid, Cone, Cylinder };
  Kind kind = Kind::Ellipsoid;
  glm::dvec3 center{0.0};  // ellipsoid: centre; cone and cylinder: centre of the bottom disc
  glm::dvec3 radii{1.0};   // ellipsoid: semi-axes; cone/cylinder: radius in x
  double height = 1.0;     // cone (apex up) and cylinder
};

bool inside(const CrownPrimitive& p, glm::dvec3 x);
// Whether the ray hits the solid primitive at some t in [t0, t1] (exact: the quadric's roots
// and the cap planes split the ray, and each piece is tested at its midpoint).
bool ray_hits(const CrownPrimitive& p, const Ray& ray, double t0, double t1);

struct SyntheticTree {
  std::vector<CrownPrimitive> parts;           // union = the tree's silhouette volume
  std::vector<std::vector<glm::dvec3>> axes;   // trunk, then first-order branches; root end first
  Bounds bounds;
  glm::dvec3 base{0.0};
};

struct CrownSpec {
  std::string shape = "ellipsoid";
  double height = 10.0;
  double width = 7.0;
  double depth = 0.0;  // crown extent along z; 0 = width (a round crown)
  double trunk_height = 2.5;
  double trunk_radius = 0.3;
  int branches = 5;
  int views = 2;
  int resolution = 128;
  bool perspective = false;
};

// Reads a `crown` table (keys above, ranges checked, errors name file:line:key).
CrownSpec read_crown_spec(const TomlTable& t);

SyntheticTree make_synthetic_tree(const CrownSpec& spec);
bool inside(const SyntheticTree& tree, glm::dvec3 x);

// Cameras for `spec` (see the header comment) framing the tree's bounds.
std::vector<Camera> synthetic_cameras(const SyntheticTree& tree, const CrownSpec& spec);

// Binary mask: a pixel is 1 when the ray through its centre hits the tree.
Mask render_mask(const SyntheticTree& tree, const Camera& camera);

// Masks, cameras and projected attractor polylines for every camera.
ViewSet synthesize_view_set(const CrownSpec& spec);

}  // namespace forest
