#include "engine/scene/terrain.h"

#include <algorithm>
#include <cmath>

#include "engine/scene/heightmap.h"
#include "generators/core/rng.h"

namespace forest {

namespace {

float lattice(uint64_t seed, int64_t ix, int64_t iz, uint32_t octave) {
  return float(hash64(seed + octave, uint64_t(ix), uint64_t(iz)) >> 11) * (1.0f / 9007199254740992.0f);
}

float smooth(float t) { return t * t * (3.0f - 2.0f * t); }

// Value noise in [0, 1] with smooth interpolation.
float value_noise(uint64_t seed, uint32_t octave, float x, float z) {
  float fx = std::floor(x), fz = std::floor(z);
  int64_t ix = int64_t(fx), iz = int64_t(fz);
  float tx = smooth(x - fx), tz = smooth(z - fz);
  float a = lattice(seed, ix, iz, octave), b = lattice(seed, ix + 1, iz, octave);
  float c = lattice(seed, ix, iz + 1, octave), d = lattice(seed, ix + 1, iz + 1, octave);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * tz;
}

}  // namespace

Terrain make_terrain(const TerrainDesc& desc) {
  Terrain t;
  t.desc = desc;
  uint32_t n = desc.resolution + 1;
  t.heights.resize(size_t(n) * n);
  float cell = desc.size / float(desc.resolution);
  if (!desc.heightmap.empty()) {
    // Image u runs along +x, v (rows, top first) along +z; both span the whole square.
    Heightmap map = read_heightmap(desc.heightmap);
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i)
        t.heights[size_t(j) * n + i] =
            desc.height_min + desc.height * map.sample(float(i) / float(desc.resolution), float(j) / float(desc.resolution));
    return t;
  }
  float norm = 0.0f;
  for (uint32_t o = 0; o < desc.octaves; ++o) norm += std::pow(0.5f, float(o));
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      float x = -0.5f * desc.size + float(i) * cell, z = -0.5f * desc.size + float(j) * cell;
      float h = 0.0f, amp = 1.0f, freq = 1.0f / desc.feature_size;
      for (uint32_t o = 0; o < desc.octaves; ++o) {
        h += amp * value_noise(desc.seed, o, x * freq, z * freq);
        amp *= 0.5f;
        freq *= 2.0f;
      }
      t.heights[size_t(j) * n + i] = (h / norm - 0.5f) * desc.height;
    }
  return t;
}

float Terrain::height_at(float x, float z) const {
  uint32_t n = desc.resolution + 1;
  float cell = desc.size / float(desc.resolution);
  float gx = std::clamp((x + 0.5f * desc.size) / cell, 0.0f, float(desc.resolution));
  float gz = std::clamp((z + 0.5f * desc.size) / cell, 0.0f, float(desc.resolution));
  uint32_t i = std::min(uint32_t(gx), desc.resolution - 1), j = std::min(uint32_t(gz), desc.resolution - 1);
  float tx = gx - float(i), tz = gz - float(j);
  auto h = [&](uint32_t a, uint32_t b) { return heights[size_t(b) * n + a]; };
  float h0 = h(i, j) + (h(i + 1, j) - h(i, j)) * tx;
  float h1 = h(i, j + 1) + (h(i + 1, j + 1) - h(i, j + 1)) * tx;
  return h0 + (h1 - h0) * tz;
}

glm::vec3 Terrain::normal_at(float x, float z) const {
  float e = 0.5f * desc.size / float(desc.resolution);
  float dx = height_at(x + e, z) - height_at(x - e, z);
  float dz = height_at(x, z + e) - height_at(x, z - e);
  return glm::normalize(glm::vec3(-dx, 2.0f * e, -dz));
}

namespace {

// The terrain's blocks of kTerrainChunkCells² cells in the order mesh() writes their indices
// and chunks() lists them: f(first cell i, first cell j, end i, end j) per block.
template <class F>
void for_each_block(uint32_t resolution, F&& f) {
  for (uint32_t cj = 0; cj < resolution; cj += kTerrainChunkCells)
    for (uint32_t ci = 0; ci < resolution; ci += kTerrainChunkCells)
      f(ci, cj, std::min(ci + kTerrainChunkCells, resolution), std::min(cj + kTerrainChunkCells, resolution));
}

}  // namespace

Mesh Terrain::mesh() const {
  Mesh m;
  uint32_t n = desc.resolution + 1;
  float cell = desc.size / float(desc.resolution);
  m.vertices.reserve(size_t(n) * n);
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      float x = -0.5f * desc.size + float(i) * cell, z = -0.5f * desc.size + float(j) * cell;
      Vertex v;
      v.position = {x, heights[size_t(j) * n + i], z};
      v.normal = normal_at(x, z);
      v.uv = {float(i) / float(desc.resolution), float(j) / float(desc.resolution)};
      m.vertices.push_back(v);
    }
  m.indices.reserve(size_t(desc.resolution) * desc.resolution * 6);
  for_each_block(desc.resolution, [&](uint32_t ci, uint32_t cj, uint32_t ie, uint32_t je) {
    for (uint32_t j = cj; j < je; ++j)
      for (uint32_t i = ci; i < ie; ++i) {
        uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
        // (i,j) -> (i,j+1) -> (i+1,j) is counter-clockwise seen from +Y.
        m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
      }
  });
  return m;
}

std::vector<TerrainChunk> Terrain::chunks() const {
  const uint32_t n = desc.resolution + 1;
  const float cell = desc.size / float(desc.resolution);
  std::vector<TerrainChunk> out;
  uint32_t first = 0;
  for_each_block(desc.resolution, [&](uint32_t ci, uint32_t cj, uint32_t ie, uint32_t je) {
    TerrainChunk c;
    c.first_index = first;
    c.index_count = (je - cj) * (ie - ci) * 6;
    float lo = INFINITY, hi = -INFINITY;
    for (uint32_t j = cj; j <= je; ++j)
      for (uint32_t i = ci; i <= ie; ++i) lo = std::min(lo, heights[size_t(j) * n + i]), hi = std::max(hi, heights[size_t(j) * n + i]);
    c.min = {-0.5f * desc.size + float(ci) * cell, lo, -0.5f * desc.size + float(cj) * cell};
    c.max = {-0.5f * desc.size + float(ie) * cell, hi, -0.5f * desc.size + float(je) * cell};
    first += c.index_count;
    out.push_back(c);
  });
  return out;
}

}  // namespace forest
