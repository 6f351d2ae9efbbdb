// Periodic noise on the unit torus for the bark textures (bark_texture.cpp): every function
// takes texture coordinates (x, y) in [0, 1) and repeats with period 1 in both, so a texture
// made of them tiles without seams. Lattice periods are whole numbers of cells per tile.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

namespace forest::bark_noise {

// Gradient (Perlin) noise on a px × py lattice per tile, about [-1, 1].
float gradient(float x, float y, int px, int py, uint64_t seed);

// Fractal sum of gradient noise: `octaves` octaves from a px × py lattice, each doubling
// the lattice and multiplying the amplitude by `gain`; normalized to about [-1, 1].
float fbm(float x, float y, int px, int py, int octaves, uint64_t seed, float gain = 0.5f);

// Worley cells of one jittered feature point per cell of an nx × ny grid per tile, distances
// in tile units (the tile is square), wrapped across the tile's edges. stretch_v > 1 makes the
// cells that many times longer along v (nearest features by a metric that shrinks v), with
// `border` still the true distance to the cell's edge.
struct Cells {
  float f1 = 0.0f;         // distance to the nearest feature point
  float border = 0.0f;     // distance to the nearest cell border (bisector of two features)
  glm::vec2 border_dir{1.0f, 0.0f};  // unit normal of that border (from this cell outward; metric)
  glm::vec2 offset{0.0f};  // from the nearest feature point to (x, y)
  uint64_t id = 0;         // hash of the nearest feature's cell: per-cell variation
};
Cells worley(float x, float y, int nx, int ny, uint64_t seed, float jitter = 0.9f, float stretch_v = 1.0f);

// Uniform in [0, 1) from a hash and a salt (per-cell random numbers).
float unit(uint64_t hash, uint64_t salt);

}  // namespace forest::bark_noise
