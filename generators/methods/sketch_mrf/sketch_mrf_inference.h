// Method `sketch-mrf`, part 1 (Neubert 2012 ch4, after Chen et al. 2008): strokes -> branch segments
// -> depths by a factor graph over parent/child segment pairs.
//
// A segment b_i ends at node i and starts at its parent node; v_i = p_i - p_parent. Its
// factor (eq. 4.16) is p(s_i) p(angle_i | label) p(gamma_i | label) with s = |v_i| / |v_p|,
// angle = divergence from the parent (alpha for the apical label 0, beta for laterals) and
// gamma = rotation about the parent direction, measured in the parent's frame. Frames are
// carried from segment to segment by parallel transport (the rotation chain
// R_c^0 = R_p^0 R_c^p); segments that start at the root have no factor and lie in the image
// plane (root z = 0, R_r^0 = I).
// Lateral gamma means: mu_gamma + pi + 2 pi (j - 1) / (K - 1) for lateral j = 1..K-1 [ours:
// the note's two rules (K = 2: + pi; K > 2: spaced 2 pi / (K - 1)) in one formula that
// agrees with both; the printed K > 2 formula would put one lateral on the apical's mean].
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "generators/methods/common/strokes_io.h"

namespace forest {

// The sketch as a tree of nodes (stroke vertices, plus the points where child strokes
// attach to their parent stroke). Node 0 is the base of the root stroke.
struct SketchTree {
  std::vector<glm::dvec2> xy;
  std::vector<int> parent;                 // -1 for node 0
  std::vector<std::vector<int>> children;
  std::vector<double> true_z;              // ground-truth depths when every stroke has them
  std::vector<glm::dvec2> crown;           // optional crown curve (role "crown")
  double height = 1.0;                     // extent of the drawing, for tolerances
};

// Strokes of role "branch" (exactly one without parent: the trunk) and an optional "crown".
// A child stroke starts at the nearest point of its parent stroke (a node is inserted
// there when it falls inside a parent segment); it must start within 10 % of the drawing's
// size of it. Errors name the stroke.
SketchTree sketch_tree_from_drawing(const Drawing& drawing);

// Global tree parameters (eq. 4.14 with the apical/lateral split): means and standard
// deviations of s, alpha (apical divergence), beta (lateral divergence), gamma. Radians.
struct Omega {
  double mu_s = 0.7, sd_s = 0.2;
  double mu_a = 0.3, sd_a = 0.2;
  double mu_b = 0.8, sd_b = 0.3;
  double mu_g = 0.0, sd_g = 1.0;
};

// gamma offset of label `label` (0 = apical) among K children.
double label_gamma_offset(int label, int K);

// All label assignments of K children (each child one label, labels unique): K! of them,
// in lexicographic order. K <= 7.
std::vector<std::vector<int>> label_hypotheses(int K);

struct SegmentAngles {
  double s = 1.0, angle = 0.0, gamma = 0.0;
};

// A segment's local frame: t along the segment, (n, b) carried by parallel transport.
struct SegmentFrame {
  glm::dvec3 t{0, 1, 0}, n{0, 0, 1}, b{1, 0, 0};
};
// The frame of a segment with vector v whose parent segment has frame `parent` (minimal
// rotation of the parent frame); segments from the root use transport_frame({}, v).
SegmentFrame transport_frame(const SegmentFrame& parent, glm::dvec3 v);
// Frames of every segment (index = end node; node 0's entry is the default frame).
std::vector<SegmentFrame> segment_frames(const SketchTree& tree, const std::vector<double>& z);

// Depth state of the sketch: z per node, label per node (its segment's label; -1 for
// segments without a parent segment).
struct SketchDepths {
  std::vector<double> z;
  std::vector<int> label;
};

// s, divergence angle and gamma of every segment given depths (frames by parallel transport
// from the root). Entries of segments without a parent segment are left default.
std::vector<SegmentAngles> segment_angles(const SketchTree& tree, const std::vector<double>& z);

// Apical = the child with the smallest 3D divergence, others lateral in order of gamma:
// the labels a procedural tree has (used for ground truth and templates).
std::vector<int> natural_labels(const SketchTree& tree, const std::vector<double>& z);

// log p(Z, L | X, Y, Omega) = sum of log factors (eq. 4.17), up to a constant.
double log_posterior(const SketchTree& tree, const SketchDepths& d, const Omega& omega);

// The ICM objective (eq. 4.24): log p_sa (s and alpha/beta) + log p_d (branch density on a
// 25^3 grid over the drawing, eq. 4.22; [ours]: d_v = share of the nodes in voxel v,
// distances in voxel units, a node does not see itself or its parent/children).
double log_p_icm(const SketchTree& tree, const SketchDepths& d, const Omega& omega, double k_e);

struct InferenceParams {
  double k_e = 5.0;           // branch interaction factor
  int em_iterations = 8;      // EM over Omega (< 10 in the source)
  bool estimate_omega = true; // false: keep the template's Omega (4.6.1)
  double icm_epsilon = 0.01;  // stop ICM when sum |dz| < epsilon * height / 10, or when a
                              // sweep raises log p by < 1e-4 (relative) [ours]
  int max_icm_sweeps = 30;
};

struct InferenceResult {
  SketchDepths depths;
  Omega omega;
  std::vector<double> icm_log_p;  // log_p_icm after every accepted ICM sweep (all E-steps)
  std::vector<Omega> omega_history;
  int em_iterations = 0;
};

// Bottom-up: per parent, the best of the K! label hypotheses, each child's depth by a 1D
// search of its factor. Root node and segments from the root at z = 0.
SketchDepths infer_bottom_up(const SketchTree& tree, const Omega& omega);
// Moves apart (along z) segments whose projections cross closer than 2 % of the height.
void separate_crossings(const SketchTree& tree, SketchDepths& d);
// ICM by per-node gradient steps with backtracking; a step is kept only when it raises
// log_p_icm, so the objective never decreases. Appends the value after every sweep.
void refine_icm(const SketchTree& tree, SketchDepths& d, const Omega& omega,
                const InferenceParams& params, std::vector<double>* log_p = nullptr);
// M-step: sample means and (maximum-likelihood) standard deviations of s, alpha, beta and
// the label-corrected gamma (circular mean); sd floors 0.02 for s and 1 degree for angles.
Omega m_step(const SketchTree& tree, const SketchDepths& d, const Omega& previous);

// E-step (bottom-up, crossings, ICM) and M-step until Omega settles or em_iterations.
InferenceResult infer_depths(const SketchTree& tree, const Omega& initial,
                             const InferenceParams& params);

}  // namespace forest
