// From least-cost paths to a renderable skeleton, shared by mig, mgv and magnetic:
// optional smoothing of the graph's zig-zag (the thesis leaves branches "a little wavy"),
// Douglas–Peucker simplification of branch chains (keeps the triangle budget), radii by
// w = s^ζ (Xu 2015 ch4.3: s = path length from the farthest tip below) or the pipe model,
// the shared foliage stage (tree/foliage.h) and model stage (model_builder.h) do the rest.
#pragma once
#include <cstdint>
#include <string>

#include "generators/tree/tree_graph.h"

namespace forest {

class TomlTable;

enum class RadiusModel { Length, Pipe };

struct SkeletonStyle {
  int smooth_iterations = 2;     // Laplacian passes over chain interiors
  float simplify = 0.0f;         // Douglas–Peucker tolerance, meters (0 = keep every node)
  RadiusModel radius_model = RadiusModel::Length;
  float tip_radius = 0.004f;     // meters
  float trunk_radius = 0.15f;    // meters at the root (Length model)
  float zeta = 0.3f;             // taper exponent of w = s^ζ
  float pipe_exponent = 2.0f;    // Pipe model
};

// The species keys read by read_skeleton_style, for a method's key list.
#define FOREST_SKELETON_STYLE_KEYS \
  "smooth", "simplify", "radius_model", "tip_radius", "trunk_radius", "zeta", "pipe_exponent"

SkeletonStyle read_skeleton_style(const TomlTable& t, const SkeletonStyle& defaults = {});

// Nodes with exactly one child and a parent are chain interiors; everything else (root,
// forks, tips) is fixed. Each pass moves an interior node halfway to its neighbours' mean.
void smooth_chains(TreeGraph& graph, int iterations);

// Keeps root, forks and tips, and the chain nodes Douglas–Peucker needs so that no removed
// node is farther than `tolerance` from the kept polyline. Order of nodes is preserved, so
// parent < own index still holds. Leaves are left untouched.
void simplify_chains(TreeGraph& graph, float tolerance);

// r = tip + (trunk − tip)·(s / s_root)^ζ with s the largest path length from the node down
// to a tip: radii strictly increase toward the root wherever edges have positive length.
void assign_length_radii(TreeGraph& graph, float tip_radius, float trunk_radius, float zeta);

size_t count_tips(const TreeGraph& graph);

// Smooth, simplify, radii; leaves cleared (the foliage stage places them). `graph` must have
// parent < own index.
TreeGraph finish_skeleton(TreeGraph graph, const SkeletonStyle& style);

}  // namespace forest
