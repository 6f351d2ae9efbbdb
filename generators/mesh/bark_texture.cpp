#include "generators/mesh/bark_texture.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/core/rng.h"
#include "generators/mesh/bark_noise.h"

namespace forest {

namespace {

namespace bn = bark_noise;

// One texel of a pattern: its height (metres above the deepest fissure) and its tone, the
// linear RGB factor of bark_color.
struct Texel {
  float height = 0.0f;
  glm::vec3 tone{1.0f};
};

float smooth01(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

glm::vec3 grey_of(glm::vec3 c) { return glm::vec3(0.3f * c.r + 0.59f * c.g + 0.11f * c.b); }

// Oak: long ridges between deep fissures that run along the branch (v). Each fissure is a
// chain of lens-shaped openings: it narrows to nothing and opens again, so the ridges beside
// it merge and part. The ridges break across now and then, their rough tops are weathered
// grey with lichen, the fissure floors dark brown.
Texel furrowed(float x, float y) {
  constexpr int kRidges = 9;  // per tile: 0.5 m / 9 = 5.5 cm from fissure to fissure
  const float s = x * kRidges + 1.3f * bn::fbm(x, y, 3, 1, 2, 10) + 0.9f * bn::fbm(x, y, 2, 2, 3, 11) +
                  0.15f * bn::fbm(x, y, 5, 12, 2, 12);
  const float f = s - std::floor(s);
  const float d = std::min(f, 1.0f - f);  // distance to the nearest fissure, in ridge periods
  const int fissure = (int(std::lround(s)) % kRidges + kRidges) % kRidges;
  const int ridge = (int(std::floor(s)) % kRidges + kRidges) % kRidges;
  const float open = smooth01(-0.35f, 0.2f, bn::gradient(0.37f * float(fissure), y, 1, 3, 13 + uint64_t(fissure)));
  const float width = (0.2f + 0.2f * bn::unit(uint64_t(fissure), 9)) * open;
  const float rough = bn::fbm(x, y, 28, 10, 3, 19);
  const float wall = smooth01(0.0f, width + 0.03f, d + 0.03f * rough);  // 0 at the floor, 1 on the ridge
  // Fine fissures splitting the ridges, shallow and mostly closed.
  const float s2 = x * kRidges * 3 + 2.0f * bn::fbm(x, y, 6, 4, 2, 20);
  const float d2 = std::abs(s2 - std::round(s2));
  const int fine_id = (int(std::lround(s2)) % (3 * kRidges) + 3 * kRidges) % (3 * kRidges);
  const float fine_open = smooth01(0.1f, 0.4f, bn::gradient(0.29f * float(fine_id), y, 1, 5, 21 + uint64_t(fine_id)));
  const float fine = (1.0f - smooth01(0.0f, 0.08f + 0.1f * fine_open, d2)) * fine_open;
  // Cross-cracks: about two per ridge and tile at jittered heights, wavy, not always across
  // the whole ridge.
  const float t = y * 2.0f + bn::unit(uint64_t(ridge), 7) * 2.0f + 0.1f * bn::fbm(x, y, 8, 3, 2, 14);
  const uint64_t block = hash64(uint64_t(ridge), uint64_t((int(std::floor(t)) % 2 + 2) % 2), 15);
  const float gap = std::abs(t - std::floor(t) - 0.3f - 0.4f * bn::unit(block, 4));
  const float reach = smooth01(0.0f, 0.12f, d - 0.25f * bn::unit(block, 5));
  const float cross = bn::unit(block, 1) < 0.4f ? (1.0f - smooth01(0.006f, 0.03f, gap)) * reach : 0.0f;
  const float fibres = bn::fbm(x, y, 48, 6, 3, 17);
  const float top = wall * (1.0f - 0.75f * cross) * (1.0f - 0.45f * fine);
  Texel out;
  out.height = 0.03f * top * top + top * (0.0025f * rough + 0.0012f * fibres);
  // Tones: the floor dark and brown, the walls brown-grey, the tops lighter and greyer, with
  // darker and lighter blotches and greenish lichen.
  const float blotch = bn::fbm(x, y, 5, 3, 3, 22);
  const float lichen = smooth01(0.15f, 0.55f, bn::fbm(x, y, 4, 3, 4, 18)) * smooth01(0.6f, 0.95f, top);
  glm::vec3 tone = glm::mix(glm::vec3(0.12f, 0.08f, 0.06f), glm::vec3(0.7f, 0.6f, 0.52f), smooth01(0.05f, 0.7f, top));
  tone = glm::mix(tone, glm::vec3(1.3f + 0.15f * rough), smooth01(0.65f, 1.0f, top));
  tone *= 1.0f + 0.1f * fibres + 0.18f * blotch * top + 0.12f * (bn::unit(block, 2) - 0.5f) * top;
  out.tone = glm::mix(tone, tone * glm::vec3(0.95f, 1.08f, 0.88f) * 1.08f, lichen);
  return out;
}

// Beech: smooth and silver-grey: blotches of lighter and darker grey at several sizes, a
// greenish cast (algae) in places, a few soft horizontal wrinkles; almost flat.
Texel smooth(float x, float y) {
  const float blotch = bn::fbm(x, y, 3, 3, 4, 21);
  const float patches = smooth01(0.05f, 0.3f, bn::fbm(x, y, 6, 5, 3, 26));  // darker, sharper-edged
  const float mottle = bn::fbm(x, y, 20, 14, 2, 22);
  const float algae = smooth01(0.2f, 0.6f, bn::fbm(x, y, 4, 3, 3, 23));
  const float wrinkle_row = y * 18.0f + 0.8f * bn::fbm(x, y, 4, 2, 2, 24);
  const float wrinkle = std::pow(std::abs(std::sin(3.14159265f * wrinkle_row)), 24.0f) *
                        smooth01(0.2f, 0.6f, bn::fbm(x, y, 5, 18, 2, 25));
  Texel t;
  t.height = 0.001f * blotch + 0.0003f * mottle - 0.0008f * wrinkle;
  t.tone = glm::vec3(1.02f + 0.12f * blotch + 0.05f * mottle - 0.12f * patches - 0.1f * wrinkle);
  t.tone *= glm::mix(glm::vec3(1.0f), glm::vec3(0.88f, 0.97f, 0.8f), 0.6f * algae);
  return t;
}

// Birch: white papery bark with grey horizontal bands of peeling skin, crossed by dark
// lenticels (dashes along u, in loose horizontal bands), and patches where it has cracked
// into dark, rough, fissured bark.
Texel birch(float x, float y) {
  Texel t;
  const float base = bn::fbm(x, y, 4, 6, 3, 31);
  const float peel = bn::fbm(x, y, 3, 30, 3, 32);  // horizontal bands: rows stretched along u
  t.tone = glm::vec3(1.12f + 0.05f * base) * glm::mix(glm::vec3(1.0f), glm::vec3(0.93f, 0.91f, 0.9f), smooth01(0.1f, 0.6f, peel));
  t.height = 0.0005f * base + 0.0004f * smooth01(0.1f, 0.6f, peel);
  // Lenticels: at most one per cell of a 4 × 22 grid, in rows that bands of noise thin out;
  // lens-shaped dashes across the branch.
  float lenticel = 0.0f;
  constexpr int nx = 4, ny = 22;
  for (int dj = -1; dj <= 1; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int i = int(std::floor(x * nx)) + di, j = int(std::floor(y * ny)) + dj;
      const uint64_t h = hash64(uint64_t((i % nx + nx) % nx), uint64_t((j % ny + ny) % ny), 33);
      const glm::vec2 centre((float(i) + bn::unit(h, 4)) / nx, (float(j) + bn::unit(h, 5)) / ny);
      const float band = 0.5f + 0.5f * bn::gradient(0.0f, centre.y, 1, 5, 37);
      if (bn::unit(h, 1) > 0.35f + 0.6f * band) continue;
      const float len = 0.015f + 0.16f * std::pow(bn::unit(h, 2), 2.0f), thick = 0.005f + 0.008f * bn::unit(h, 3);
      glm::vec2 d = glm::vec2(x, y) - centre;
      d.y += 0.004f * bn::gradient(x, 0.0f, 24, 1, 38 + (h & 7));  // slightly wavy
      const float th = thick * (1.0f - 0.7f * std::min(1.0f, std::abs(d.x) / (0.5f * len)));
      d.x = std::max(std::abs(d.x) - 0.5f * len, 0.0f);
      lenticel = std::max(lenticel, (0.6f + 0.4f * bn::unit(h, 6)) * (1.0f - smooth01(0.4f * th, th + 0.0015f, glm::length(d))));
    }
  // Dark patches where slow noise is high, rough and fissured along v inside.
  const float slow = bn::fbm(x, y, 2, 5, 4, 34);  // patches elongated across the branch
  const float patch = smooth01(0.3f, 0.38f, slow + 0.12f * bn::fbm(x, y, 12, 8, 2, 35));
  const bn::Cells c = bn::worley(x, y, 16, 6, 36, 0.9f);
  const float rough = smooth01(0.0f, 0.005f + 0.012f * std::abs(c.border_dir.x), c.border);
  const glm::vec3 dark = glm::vec3(0.07f, 0.065f, 0.06f) * (0.6f + 1.2f * rough);
  // Grey smudges around the patches: the white skin thinning.
  const float smudge = smooth01(0.12f, 0.3f, slow) * (1.0f - patch);
  t.height += patch * (0.005f * rough - 0.002f) - 0.001f * lenticel * (1.0f - patch);
  t.tone *= 1.0f - 0.3f * smudge;
  t.tone = glm::mix(t.tone, glm::vec3(0.1f, 0.09f, 0.085f), lenticel);
  t.tone = glm::mix(t.tone, dark, patch);
  return t;
}

// Pine: irregular plates, longer along the branch than across, between deep dark fissures;
// each plate is covered with thin flakes (smaller cells) whose lower edges stand out a
// little. Under the flakes the bark is orange, the weathered outer flakes are greyer.
Texel scaly(float x, float y) {
  const float wx = x + 0.025f * bn::fbm(x, y, 4, 4, 3, 41), wy = y + 0.025f * bn::fbm(x, y, 4, 4, 3, 42);
  const bn::Cells c = bn::worley(wx, wy, 7, 3, 43, 1.0f, 2.2f);
  const float ragged = 0.005f * bn::fbm(x, y, 24, 24, 2, 46);
  const float gap = smooth01(0.003f, 0.02f, c.border + ragged);
  const bn::Cells flake = bn::worley(x + 0.01f * bn::fbm(x, y, 16, 16, 2, 47), y, 22, 12, 44, 0.95f, 1.3f);
  // Flake edges show where a flake lies over the next one (its edge toward the base, +v),
  // and only on some flakes.
  const bool shows = bn::unit(flake.id, 3) < 0.6f && flake.border_dir.y > 0.3f;
  const float flake_edge = shows ? smooth01(0.0f, 0.005f, flake.border) : 1.0f;
  const float lift = std::clamp(0.5f + flake.offset.y * 24.0f, 0.0f, 1.0f);  // rises toward +v
  const float grain = bn::fbm(x, y, 40, 20, 2, 45);
  Texel out;
  out.height = gap * (0.014f + 0.0015f * flake_edge * (1.0f + lift)) + 0.0005f * grain;
  // Weathered grey-brown on the plates' outer layers, orange where flakes have come off.
  const float weathered = smooth01(0.3f, 0.7f, 0.5f * bn::unit(c.id, 2) + 0.5f * bn::unit(flake.id, 1) +
                                                   0.3f * bn::fbm(x, y, 6, 4, 2, 49));
  glm::vec3 plate = glm::mix(glm::vec3(1.45f, 0.98f, 0.72f), glm::vec3(0.92f, 0.82f, 0.76f), weathered);
  plate *= (0.75f + 0.25f * flake_edge) * (0.9f + 0.1f * lift) + 0.07f * grain;
  out.tone = glm::mix(glm::vec3(0.16f, 0.1f, 0.07f), plate, gap);
  return out;
}

// Spruce: small rounded scales overlapping like shingles (of two that overlap, the one
// nearer the base, +v, lies on top), each a low dome with a slightly ragged rim darkened
// where it casts its edge; dark under-bark shows through where none covers it.
Texel plated(float x, float y) {
  constexpr int nx = 12, ny = 9;  // per tile: 0.4 m / 12 = 3.3 cm wide scales
  const int ci = int(std::floor(x * nx)), cj = int(std::floor(y * ny));
  float top_rank = -1e9f, r_top = 2.0f;
  glm::vec2 d_top(0.0f);
  uint64_t id = 0;
  for (int dj = -2; dj <= 2; ++dj)
    for (int di = -1; di <= 1; ++di) {
      const int i = ci + di, j = cj + dj;
      const uint64_t h = hash64(uint64_t((i % nx + nx) % nx), uint64_t((j % ny + ny) % ny), 53);
      const glm::vec2 centre((float(i) + 0.5f + 0.8f * (bn::unit(h, 1) - 0.5f)) / nx,
                             (float(j) + 0.5f + 0.8f * (bn::unit(h, 2) - 0.5f)) / ny);
      const float radius = (0.5f + 0.5f * bn::unit(h, 3)) / nx;
      const glm::vec2 d = (glm::vec2(x, y) - centre) / (radius * glm::vec2(1.0f, 1.1f + 0.3f * bn::unit(h, 8)));
      const float angle = std::atan2(d.y, d.x);
      const float r = glm::length(d) * (1.0f + 0.18f * bn::gradient(angle / 6.2831853f + 0.5f, bn::unit(h, 4), 5, 1, 54));
      if (r >= 1.0f || centre.y <= top_rank) continue;
      top_rank = centre.y, r_top = r, d_top = d, id = h;
    }
  const float grain = bn::fbm(x, y, 36, 36, 2, 55);
  Texel t;
  if (r_top >= 1.0f) {  // under-bark between the scales
    t.height = 0.0004f * grain;
    t.tone = glm::vec3(0.3f, 0.22f, 0.18f);
    return t;
  }
  const float dome = std::sqrt(1.0f - r_top * r_top);
  const float lift = std::clamp(0.5f + 0.5f * d_top.y, 0.0f, 1.0f);  // the edge toward the base stands out
  const float rim = smooth01(0.75f, 1.0f, r_top);
  t.height = 0.0015f + 0.0008f * dome + 0.0015f * lift * (1.0f - rim) + 0.0003f * grain;
  glm::vec3 scale = glm::vec3(1.0f + 0.25f * (bn::unit(id, 5) - 0.5f));
  if (bn::unit(id, 6) > 0.6f) scale *= glm::vec3(1.15f, 0.95f, 0.88f);  // fresher, reddish scales
  if (bn::unit(id, 7) > 0.8f) scale = glm::mix(scale, grey_of(scale) * 1.15f, 0.6f);  // weathered grey
  t.tone = scale * (0.9f + 0.1f * dome + 0.08f * grain) * (1.0f - 0.3f * rim * (1.0f - lift));
  return t;
}

// Any other species: fine fibres along v and shallow fissures that open and close along it,
// a middle ground between smooth and furrowed barks.
Texel generic(float x, float y) {
  constexpr int kFissures = 7;  // per tile: 0.5 m / 7 = 7 cm apart
  const float s = x * kFissures + 0.9f * bn::fbm(x, y, 3, 1, 2, 61) + 0.5f * bn::fbm(x, y, 2, 3, 3, 62);
  const float d = std::abs(s - std::round(s));
  const int fissure = (int(std::lround(s)) % kFissures + kFissures) % kFissures;
  const float open = smooth01(-0.45f, 0.1f, bn::gradient(0.41f * float(fissure), y, 1, 3, 63 + uint64_t(fissure)));
  const float fibres = bn::fbm(x, y, 40, 5, 4, 64);
  const float blotch = bn::fbm(x, y, 4, 3, 3, 65);
  const float top = 1.0f - open * (1.0f - smooth01(0.02f, 0.06f + 0.16f * open, d + 0.02f * fibres));
  Texel t;
  t.height = 0.008f * top + 0.001f * fibres;
  t.tone = glm::vec3(0.35f + 0.75f * top * top + 0.12f * fibres + 0.1f * blotch);
  return t;
}

Texel sample(BarkPattern p, float x, float y) {
  switch (p) {
    case BarkPattern::furrowed: return furrowed(x, y);
    case BarkPattern::smooth: return smooth(x, y);
    case BarkPattern::birch: return birch(x, y);
    case BarkPattern::scaly: return scaly(x, y);
    case BarkPattern::plated: return plated(x, y);
    case BarkPattern::generic: break;
  }
  return generic(x, y);
}

uint8_t linear_to_srgb8(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  float e = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(e * 255.0f));
}

uint8_t unorm8(float c) { return uint8_t(std::lround(std::clamp(c * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

std::optional<BarkPattern> parse_bark_pattern(std::string_view name) {
  for (BarkPattern p : {BarkPattern::furrowed, BarkPattern::smooth, BarkPattern::birch, BarkPattern::scaly,
                        BarkPattern::plated, BarkPattern::generic})
    if (name == bark_pattern_name(p)) return p;
  return std::nullopt;
}

const char* bark_pattern_name(BarkPattern pattern) {
  switch (pattern) {
    case BarkPattern::furrowed: return "furrowed";
    case BarkPattern::smooth: return "smooth";
    case BarkPattern::birch: return "birch";
    case BarkPattern::scaly: return "scaly";
    case BarkPattern::plated: return "plated";
    case BarkPattern::generic: return "generic";
  }
  return "generic";
}

float bark_tile_meters(BarkPattern pattern) {
  switch (pattern) {
    case BarkPattern::furrowed: return 0.5f;
    case BarkPattern::smooth: return 1.0f;
    case BarkPattern::birch: return 0.5f;
    case BarkPattern::scaly: return 0.6f;
    case BarkPattern::plated: return 0.4f;
    case BarkPattern::generic: return 0.5f;
  }
  return 0.5f;
}

BarkTextures make_bark_textures(BarkPattern pattern, glm::vec3 bark_color, uint32_t size) {
  const size_t n = size_t(size) * size;
  std::vector<float> height(n);
  BarkTextures out;
  out.albedo.width = out.albedo.height = out.normal.width = out.normal.height = size;
  out.albedo.rgba.resize(n * 4);
  out.normal.rgba.resize(n * 4);
  for (uint32_t py = 0; py < size; ++py)
    for (uint32_t px = 0; px < size; ++px) {
      const Texel t = sample(pattern, (float(px) + 0.5f) / float(size), (float(py) + 0.5f) / float(size));
      const size_t i = size_t(py) * size + px;
      height[i] = t.height;
      const glm::vec3 c = bark_color * t.tone;
      uint8_t* a = &out.albedo.rgba[i * 4];
      a[0] = linear_to_srgb8(c.r), a[1] = linear_to_srgb8(c.g), a[2] = linear_to_srgb8(c.b), a[3] = 255;
    }
  // Normals of the height field (metres over metres: slopes in the tile's physical size),
  // central differences wrapped across the edges. Rows grow with v, and +Y is toward the
  // top row, so dh/dY = −dh/drow.
  const float texel = bark_tile_meters(pattern) / float(size);
  auto h = [&](uint32_t x, uint32_t y) { return height[size_t(y % size) * size + (x % size)]; };
  for (uint32_t py = 0; py < size; ++py)
    for (uint32_t px = 0; px < size; ++px) {
      const float dx = (h(px + 1, py) - h(px + size - 1, py)) / (2.0f * texel);
      const float drow = (h(px, py + 1) - h(px, py + size - 1)) / (2.0f * texel);
      const glm::vec3 nrm = glm::normalize(glm::vec3(-dx, drow, 1.0f));
      uint8_t* q = &out.normal.rgba[(size_t(py) * size + px) * 4];
      q[0] = unorm8(nrm.x), q[1] = unorm8(nrm.y), q[2] = unorm8(nrm.z), q[3] = 255;
    }
  return out;
}

}  // namespace forest
