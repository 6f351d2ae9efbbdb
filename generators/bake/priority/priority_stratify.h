// Spatially stratified leaf orders [ours]: every prefix of the order keeps each region of
// the crown in proportion to the leaves it holds.
//
// Why: the run time draws a prefix of ⌈λN⌉ leaves and widens each by one scale s(λ) for the
// whole tree, which assumes the prefix thins every part of the crown by the same λ. The
// paper's orders break that (Neubert 2012 §7.3): the density order keeps the sparse fringe
// and empties dense clumps, the orientation order keeps the leaves facing along the hull,
// which cluster where the crown's surface is flat. Measured on a dense broadleaf (7 095
// leaves, bench/species/broadleaf_dense.toml), the prefix at λ = 0.3 holds regions
// 2.5–3.6 × more unevenly than a random prefix, and the geometry these orders save against
// Cook falls below random's (bench/results/table7_4.md, bake_bench --variants). Stratifying keeps each order's choice of
// *which* leaves in a region survive and takes *how many* from the region's size.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace forest {

// `order` (descending survival, a permutation of 0..N-1) re-merged so that within every
// cubic cell of edge `cell` (model units) the leaves keep their relative order, and the
// k-th leaf of a cell of n leaves lands where a fraction (k + u) / n of the order has gone,
// u a seeded per-cell offset in [0, 1). Any prefix of length λN then holds each cell's
// ⌊λn⌋ or ⌈λn⌉ best leaves (up to one leaf). cell <= 0 returns order unchanged.
std::vector<uint32_t> stratify_order(std::span<const uint32_t> order, std::span<const glm::vec3> centers,
                                     float cell, uint64_t seed);

}  // namespace forest
