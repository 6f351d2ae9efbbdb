#include "generators/mesh/bark_noise.h"

#include <cmath>

#include "generators/core/rng.h"

namespace forest::bark_noise {

namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// 16 unit gradients (a table, not sin/cos per corner: faster, and the same on every libm).
const glm::vec2& gradient_of(uint64_t h) {
  static const glm::vec2 kTable[16] = {
      {1.0f, 0.0f},         {0.92388f, 0.38268f},  {0.70711f, 0.70711f},  {0.38268f, 0.92388f},
      {0.0f, 1.0f},         {-0.38268f, 0.92388f}, {-0.70711f, 0.70711f}, {-0.92388f, 0.38268f},
      {-1.0f, 0.0f},        {-0.92388f, -0.38268f}, {-0.70711f, -0.70711f}, {-0.38268f, -0.92388f},
      {0.0f, -1.0f},        {0.38268f, -0.92388f}, {0.70711f, -0.70711f},  {0.92388f, -0.38268f}};
  return kTable[h & 15u];
}

}  // namespace

float unit(uint64_t hash, uint64_t salt) { return float(mix64(hash ^ (salt * 0x9E3779B97F4A7C15ull)) >> 40) / 16777216.0f; }

float gradient(float x, float y, int px, int py, uint64_t seed) {
  const float cx = x * float(px), cy = y * float(py);
  const float fx = std::floor(cx), fy = std::floor(cy);
  const int ix = int(fx), iy = int(fy);
  const float tx = cx - fx, ty = cy - fy;
  auto corner = [&](int di, int dj) {
    const glm::vec2& g = gradient_of(hash64(uint64_t(wrap(ix + di, px)), uint64_t(wrap(iy + dj, py)), seed));
    return g.x * (tx - float(di)) + g.y * (ty - float(dj));
  };
  const float u = fade(tx), v = fade(ty);
  const float a = corner(0, 0) + u * (corner(1, 0) - corner(0, 0));
  const float b = corner(0, 1) + u * (corner(1, 1) - corner(0, 1));
  return 1.41421f * (a + v * (b - a));  // 2D Perlin noise stays within ±1/√2
}

float fbm(float x, float y, int px, int py, int octaves, uint64_t seed, float gain) {
  float sum = 0.0f, amplitude = 1.0f, norm = 0.0f;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * gradient(x, y, px << o, py << o, seed + uint64_t(o) * 7919u);
    norm += amplitude;
    amplitude *= gain;
  }
  return sum / norm;
}

Cells worley(float x, float y, int nx, int ny, uint64_t seed, float jitter, float stretch_v) {
  const glm::vec2 metric(1.0f, 1.0f / stretch_v);
  // Candidates: the features of the 5 × 5 cells around (x, y), as metric offsets (cells may
  // be elongated, so ±2 cells are searched to find the true nearest two).
  constexpr int kReach = 2, kSide = 2 * kReach + 1;
  glm::vec2 feature[kSide * kSide];
  uint64_t ids[kSide * kSide];
  const float cx = x * float(nx), cy = y * float(ny);
  const int ix = int(std::floor(cx)), iy = int(std::floor(cy));
  int nearest = 0, n = 0;
  float best = 1e30f;
  for (int dj = -kReach; dj <= kReach; ++dj)
    for (int di = -kReach; di <= kReach; ++di, ++n) {
      const int i = ix + di, j = iy + dj;
      const uint64_t h = hash64(uint64_t(wrap(i, nx)), uint64_t(wrap(j, ny)), seed);
      const float jx = 0.5f + jitter * (unit(h, 1) - 0.5f), jy = 0.5f + jitter * (unit(h, 2) - 0.5f);
      feature[n] = metric * glm::vec2((float(i) + jx) / float(nx) - x, (float(j) + jy) / float(ny) - y);
      ids[n] = h;
      const float d = glm::dot(feature[n], feature[n]);
      if (d < best) best = d, nearest = n;
    }
  Cells c;
  const glm::vec2 a = feature[nearest];
  c.f1 = std::sqrt(best);
  c.offset = -a / metric;
  c.id = ids[nearest];
  c.border = 1e30f;
  for (int k = 0; k < kSide * kSide; ++k) {
    if (k == nearest) continue;
    const glm::vec2 ab = feature[k] - a;
    const float len = glm::length(ab);
    if (!(len > 0.0f)) continue;
    const glm::vec2 dir = ab / len;
    // The metric distance to the bisector, over the metric's rate along its normal: the
    // distance in the tile.
    const float d = glm::dot(0.5f * (a + feature[k]), dir) / glm::length(metric * dir);  // (x, y) is the origin
    if (d < c.border) c.border = d, c.border_dir = dir;
  }
  return c;
}

}  // namespace forest::bark_noise
