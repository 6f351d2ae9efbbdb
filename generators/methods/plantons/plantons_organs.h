// Organs of the plantons method (Wang 2006, §3.1): a tree sample is a set of
// organs O (o_1 the root, parent index < child index) and growth relations B (each organ's
// parent). Two organ types: a stem is one branch axis (a cubic Bézier centre line with a base
// and a tip radius), a leaf is a blade; flowers are not modeled (no method makes them).
// Every organ also records where it grows on its parent (t ∈ [0, 1], the Bézier parameter)
// and in which direction: θ from the parent's tangent at t, and φ the azimuth around it.
// [ours] φ is the divergence from the previous sibling (siblings in order of t; the first
// measured from the tangent's upper side): with independent absolute azimuths a fork's
// children often all land on one side, while divergences reproduce phyllotaxis and forks.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/tree/tree_graph.h"

namespace forest {

enum class OrganType : uint8_t { Stem = 0, Leaf = 1 };
constexpr int kOrganTypes = 2;
const char* organ_type_name(OrganType type);

// Parameter vector s (eq. 1) of each type. Stem: chord length L (m), base radius, tip radius,
// then the inner Bézier control points P1, P2 relative to P0, divided by L, in the stem's
// frame (x toward the world-up side, y along the chord, z = x × y). Leaf: blade length.
constexpr int kStemParams = 9;
constexpr int kLeafParams = 1;
int organ_param_count(OrganType type);

struct Organ {
  OrganType type = OrganType::Stem;
  int32_t parent = -1;            // index of the parent organ; -1 for the root
  double t = 0.0;                 // position on the parent's centre line (Bézier parameter)
  double theta = 0.0;             // radians between the parent's tangent at t and `direction`
  double phi = 0.0;               // divergence from the previous sibling, radians, (−π, π]
  std::vector<double> s;          // organ_param_count(type) parameters
  glm::vec3 base{0.0f};           // world position where the organ starts
  glm::vec3 direction{0, 1, 0};   // stem chord / leaf blade axis, unit
};

struct OrganTree {
  std::vector<Organ> organs;  // organs[0] is the root stem; parent < own index
};

// Frame of a direction d: x = the part of world up perpendicular to d (world X when d is
// vertical), y = d, z = x × y. Used for the stem parameters and for θ/φ alike.
struct OrganFrame {
  glm::dvec3 x, y, z;
};
OrganFrame organ_frame(glm::dvec3 d);

// Direction from (θ, φ) in the frame of `tangent`, and back.
glm::dvec3 direction_from_angles(glm::dvec3 tangent, double theta, double phi);
void angles_of_direction(glm::dvec3 tangent, glm::dvec3 d, double& theta, double& phi);

// World Bézier control points of a stem organ (from base, direction and s).
std::array<glm::dvec3, 4> stem_control_points(const Organ& stem);
glm::dvec3 bezier_point(const std::array<glm::dvec3, 4>& p, double u);
glm::dvec3 bezier_tangent(const std::array<glm::dvec3, 4>& p, double u);  // unit

// Least-squares cubic Bézier through points (chord-length parameters, ends fixed); returns
// the control points and writes each point's parameter to `u`.
std::array<glm::dvec3, 4> fit_bezier(const std::vector<glm::dvec3>& points, std::vector<double>& u);

// Turns absolute azimuths (from the upper side of each parent's tangent) into divergences
// from the previous sibling, siblings ordered by t then index.
void azimuths_to_divergences(OrganTree& tree);
double wrap_angle(double a);  // into (−π, π]

// Organs of a TreeGraph. A stem is an axis: from its first node it continues into the child
// with the same TreeNode::order, the straightest of them; the other children start new axes
// at that point. (Splitting at every fork instead would put every child at t = 1 and leave
// the position distribution T empty.) Each leaf is attached to the axis of its nearest node.
// Organs come breadth-first, so parent < own index. Throws InputError when the graph has no
// branch.
OrganTree organs_from_graph(const TreeGraph& graph);

struct OrganMeshing {
  int segments = 6;              // nodes along each stem (plus one per child attachment)
  float min_radius = 0.002f;     // m
};

// The TreeGraph of an organ tree (the inverse of organs_from_graph up to the Bézier fit): each
// stem becomes a chain of nodes along its Bézier curve with radii interpolated base → tip,
// children start at the node placed at their t; leaves become leaf placements whose blades
// face away from a point inside the crown.
TreeGraph graph_from_organs(const OrganTree& tree, const OrganMeshing& meshing = {});

}  // namespace forest
