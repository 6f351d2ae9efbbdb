#include "generators/mesh/leaf_texture.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/core/rng.h"

namespace forest {

namespace {

constexpr float kPetiole = 0.08f;  // stalk length, fraction of the card length
constexpr float kMargin = 0.02f;   // empty border around the outline (filtering)

// Outline of a broad blade: half-width W · τ^a (1 − τ)^b / max over the blade τ ∈ [0, 1]:
// a < 1 rounds the base, b ≥ 1 makes a pointed tip; the widest point is at a / (a + b).
struct Blade {
  float half_width, a, b;
};

Blade blade_of(LeafShape s) {
  switch (s) {
    case LeafShape::ovate: return {0.30f, 0.55f, 1.0f};
    case LeafShape::elliptic: return {0.26f, 0.8f, 0.9f};
    case LeafShape::lanceolate: return {0.12f, 0.5f, 1.3f};
    case LeafShape::lobed: return {0.30f, 1.1f, 0.75f};   // widest above the middle
    case LeafShape::deltoid: return {0.34f, 0.28f, 1.15f};  // widest near the base
    case LeafShape::palmate: return {0.46f, 1.0f, 1.0f};  // outline is polar (palmate_class)
    case LeafShape::needles: break;
  }
  return {0.0f, 1.0f, 1.0f};
}

float blade_profile(const Blade& bl, float tau) {
  if (tau <= 0.0f || tau >= 1.0f) return 0.0f;
  float peak = bl.a / (bl.a + bl.b);
  float norm = std::pow(peak, bl.a) * std::pow(1.0f - peak, bl.b);
  return bl.half_width * std::pow(tau, bl.a) * std::pow(1.0f - tau, bl.b) / norm;
}

float segment_distance(float x, float y, float ax, float ay, float bx, float by) {
  float dx = bx - ax, dy = by - ay;
  float t = std::clamp(((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy), 0.0f, 1.0f);
  float ex = x - ax - t * dx, ey = y - ay - t * dy;
  return std::sqrt(ex * ex + ey * ey);
}

// One needle: a capsule from the twig outward.
struct Needle {
  float ax, ay, bx, by;
};

// Needles on both sides of the twig, alternating between a flatter and a steeper angle
// (seen from above a spruce shoot the needles stand in several ranks), shorter toward the tip.
std::vector<Needle> needle_spray() {
  std::vector<Needle> out;
  const int rows = 24;
  for (int i = 0; i < rows; ++i) {
    float y = 0.08f + 0.86f * float(i) / float(rows - 1);
    for (float side : {-1.0f, 1.0f}) {
      float angle = ((i + (side > 0.0f)) % 2 ? 45.0f : 64.0f) * 3.14159265f / 180.0f;  // from the twig
      float len = 0.30f * (1.0f - 0.45f * y);
      out.push_back({0.0f, y, side * len * std::sin(angle), y + len * std::cos(angle)});
    }
  }
  out.push_back({0.0f, 0.92f, 0.0f, 1.0f - kMargin});  // the leading shoot
  return out;
}

// The margin of a pinnate blade: fine teeth, double teeth (deltoid) or rounded lobes with
// small ear-like lobes at the base (lobed: Quercus robur's auricles).
float margin_factor(LeafShape shape, float tau) {
  switch (shape) {
    case LeafShape::lobed: {
      float lobe = std::pow(std::abs(std::sin(3.14159265f * 4.5f * tau)), 0.7f);
      float ear = tau < 0.12f ? 0.5f * (1.0f - tau / 0.12f) : 0.0f;
      return 0.58f + 0.42f * lobe + ear;
    }
    case LeafShape::deltoid:
      return 1.0f + 0.04f * std::sin(tau * 150.0f) + 0.03f * std::sin(tau * 52.0f);
    default: return 1.0f + 0.025f * std::sin(tau * 110.0f);
  }
}

// Field maple: five rounded lobes around the top of the petiole, each with its own primary
// vein radiating from there (palmate venation).
int palmate_class(float x, float y) {
  const float cx = 0.0f, cy = kPetiole + 0.40f;
  if (y < cy && std::abs(x) < 0.009f && y >= 0.0f) return 3;  // petiole up to the blade centre
  const float dx = x - cx, dy = y - cy;
  const float rho = std::sqrt(dx * dx + dy * dy), theta = std::atan2(dx, dy);  // 0 = toward the tip
  static constexpr float kLobes[] = {0.0f, 1.15f, -1.15f, 2.2f, -2.2f};
  static constexpr float kReach[] = {0.50f, 0.44f, 0.44f, 0.30f, 0.30f};
  float reach = 0.16f;
  int nearest = 0;
  for (int l = 0; l < 5; ++l) {
    float d = (theta - kLobes[l]) / 0.45f;
    float r = 0.16f + (kReach[l] - 0.16f) * std::exp(-d * d);
    if (r > reach) reach = r, nearest = l;
  }
  if (std::abs(theta) > 2.75f) reach = std::min(reach, 0.10f);  // the sinus at the petiole
  reach *= 1.0f + 0.03f * std::sin(theta * 40.0f);
  if (rho >= reach) return 0;
  // Primary veins: distance to the ray of the nearest lobe, tapering outward.
  float lx = std::sin(kLobes[nearest]), ly = std::cos(kLobes[nearest]);
  float along = dx * lx + dy * ly, across = std::abs(dx * ly - dy * lx);
  if (along > 0.0f && across < 0.010f * (1.0f - rho / reach) + 0.002f) return 3;
  // Secondary veins leave the primary one at 45 degrees, every 0.07.
  float phase = (along - across) / 0.07f;
  float dv = std::abs(phase - std::round(phase)) * 0.07f * 0.707f;
  if (along > 0.05f && rho < 0.85f * reach && dv < 0.003f) return 2;
  return 1;
}

const std::vector<Needle>& needles() {
  static const std::vector<Needle> spray = needle_spray();
  return spray;
}

}  // namespace

int leaf_texel_class(LeafShape shape, float x, float y, float stroke) {
  const float ax = std::abs(x);
  if (shape == LeafShape::needles) {
    if (y >= 0.0f && y <= 0.94f && ax < stroke * 0.010f * (1.0f - 0.5f * y)) return 3;  // twig
    for (const Needle& n : needles())
      if (segment_distance(x, y, n.ax, n.ay, n.bx, n.by) < stroke * 0.011f) return 1;
    return 0;
  }
  if (shape == LeafShape::palmate) return palmate_class(x, y);
  if (y < 0.0f || y > 1.0f) return 0;
  if (y < kPetiole + 0.01f && ax < 0.009f) return 3;  // petiole
  const Blade bl = blade_of(shape);
  float tau = (y - kPetiole) / (1.0f - kPetiole);
  float h = blade_profile(bl, tau) * margin_factor(shape, tau);
  if (ax >= h) return 0;
  // Vein widths scale with the blade's width.
  const float k = bl.half_width / 0.3f;
  if (ax < k * (0.011f * (1.0f - 0.7f * tau) + 0.002f)) return 3;  // midrib, tapering
  // Pinnate secondary veins: straight lines leaving the midrib toward the tip.
  const float slope = 0.9f, spacing = 0.085f;
  float y0 = y - ax * slope;  // where this point's vein line meets the midrib
  float phase = (y0 - kPetiole) / spacing;
  float d = std::abs(phase - std::round(phase)) * spacing / std::sqrt(1.0f + slope * slope);
  if (phase > 0.5f && ax < 0.85f * h && d < k * (0.0045f * (1.0f - ax / h) + 0.0015f)) return 2;
  return 1;
}


std::optional<LeafShape> parse_leaf_shape(std::string_view name) {
  for (LeafShape s : kLeafShapes)
    if (name == leaf_shape_name(s)) return s;
  return std::nullopt;
}

const char* leaf_shape_name(LeafShape shape) {
  switch (shape) {
    case LeafShape::ovate: return "ovate";
    case LeafShape::elliptic: return "elliptic";
    case LeafShape::lanceolate: return "lanceolate";
    case LeafShape::lobed: return "lobed";
    case LeafShape::deltoid: return "deltoid";
    case LeafShape::palmate: return "palmate";
    case LeafShape::needles: return "needles";
  }
  return "ovate";
}

float leaf_card_aspect(LeafShape shape) {
  if (shape == LeafShape::needles) return 2.0f * (0.30f * std::sin(64.0f * 3.14159265f / 180.0f) + kMargin);
  const float teeth = shape == LeafShape::lobed ? 1.0f : shape == LeafShape::deltoid ? 1.07f : 1.03f;
  if (shape == LeafShape::palmate) return 2.0f * (0.46f + kMargin);
  return 2.0f * (blade_of(shape).half_width * teeth + kMargin);
}

Image8 make_leaf_texture(LeafShape shape, uint32_t size) {
  Image8 img;
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size * 4);
  const float w = leaf_card_aspect(shape);
  constexpr int kSub = 4;  // 4 x 4 samples per texel: 16 coverage levels
  // Shades (multipliers of the model's leaf color): blade, vein, midrib.
  const float shade[4] = {1.0f, 1.0f, 0.72f, 0.58f};
  for (uint32_t py = 0; py < size; ++py)
    for (uint32_t px = 0; px < size; ++px) {
      int covered = 0;
      float tone = 0.0f;
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          float u = (float(px) + (float(sx) + 0.5f) / kSub) / float(size);
          float v = (float(py) + (float(sy) + 0.5f) / kSub) / float(size);
          int c = leaf_texel_class(shape, (u - 0.5f) * w, 1.0f - v);
          if (c) ++covered, tone += shade[c];
        }
      // Blade tone with a little deterministic mottling; transparent texels get the blade's.
      float mottle = 1.0f - 0.06f * float(hash64(px / 3, py / 3, 0x1eaf) % 1000u) / 1000.0f;
      float t = covered ? tone / float(covered) : 1.0f;
      float g = t * mottle;
      uint8_t* out = &img.rgba[(size_t(py) * size + px) * 4];
      out[0] = uint8_t(std::lround(255.0f * std::clamp(g * 0.97f, 0.0f, 1.0f)));
      out[1] = uint8_t(std::lround(255.0f * std::clamp(g, 0.0f, 1.0f)));
      out[2] = uint8_t(std::lround(255.0f * std::clamp(g * 0.90f, 0.0f, 1.0f)));
      out[3] = uint8_t((covered * 255 + kSub * kSub / 2) / (kSub * kSub));
    }
  return img;
}

}  // namespace forest
