// Where plantons learns from: the synthetic ground truth of the reference note (plantons
// T, P, S, L with known parameters), trees generated in-process from any method's species
// preset, or a sample file (JSON TreeGraphs, written by `forest make-inputs`).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "generators/methods/plantons/plantons_model.h"
#include "generators/tree/tree_graph.h"

namespace forest {

// Ground truth [ours, after the reference note]: T trunk (ℓ ~ N(8, 0.3²), children ~
// N(6, 0.5²), T→P p = 1, t ~ N(0.6, 0.15²), θ ~ N(50°, 5²)); P (ℓ ~ N(3, 0.2²), children ~
// N(4, 0.5²), P→S 0.75, P→L 0.25); S (ℓ ~ N(1, 0.1²), children ~ N(5, 0.5²), S→L 1); L leaf.
// About 120 organs per tree. Parameters are in raw units (α = 1) and there are no exemplars:
// synthesis uses the sampled parameters directly.
PlantonModel ground_truth_model();
// Planton of each ground-truth organ is SynthesizedTree::plantons (0 T, 1 P, 2 S, 3 L).
std::vector<OrganTree> ground_truth_samples(size_t count, uint64_t seed,
                                            std::vector<std::vector<uint32_t>>* truth = nullptr);

// Sample trees from species presets: `count` trees per file, tree k with seed `seed + k`.
std::vector<TreeGraph> species_samples(const std::vector<std::filesystem::path>& species, size_t count,
                                       uint64_t seed);

// Sample file: {"format": "forest-samples", "version": 1, "trees": [{"nodes": [[x, y, z,
// radius, parent, order], ...], "leaves": [[x, y, z, qw, qx, qy, qz, scale], ...]}]}.
std::string samples_to_text(const std::vector<TreeGraph>& trees);
void save_samples(const std::vector<TreeGraph>& trees, const std::filesystem::path& path);
std::vector<TreeGraph> parse_samples(const std::string& text, const std::string& name);
std::vector<TreeGraph> load_samples(const std::filesystem::path& path);

// `forest make-inputs`: dir/ground_truth.json, three ground-truth trees.
void plantons_make_inputs(const std::filesystem::path& dir);

}  // namespace forest
