#include "generators/mesh/foliage_card.h"

#include <algorithm>
#include <cmath>

#include "generators/core/rng.h"

namespace forest {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kTwigEnd = 0.97f;     // the twig runs from the base to here, card units
constexpr float kTwigWidth = 0.012f;  // half-width at the base, tapering to a third

float leaf_aspect(LeafShape shape) { return leaf_card_aspect(shape); }

}  // namespace

std::vector<ShootLeaf> shoot_leaves(const ShootDesign& d) {
  std::vector<ShootLeaf> out;
  if (d.single_leaf) return out;
  const int n = std::max(1, d.leaves);
  const float len = std::clamp(d.leaf_length, 0.05f, 0.9f);
  // The terminal leaf continues the twig; it ends at the card's top.
  ShootLeaf top;
  top.length = std::min(len, 1.0f - 0.02f - 0.55f);
  top.base = glm::vec2(0.0f, 1.0f - 0.02f - top.length);
  out.push_back(top);
  const int lateral = n - 1;
  if (lateral == 0) return out;
  const int per_node = leaves_at_node(d.phyllotaxis, 3);
  const int nodes = (lateral + per_node - 1) / per_node;
  // Nodes from just above the base to below the terminal leaf; leaves shorter and steeper
  // toward the tip, as on a real shoot whose youngest leaves are still expanding.
  const float y0 = 0.10f, y1 = std::max(y0, top.base.y - 0.02f);
  int placed = 0;
  for (int k = 0; k < nodes && placed < lateral; ++k) {
    float t = nodes == 1 ? 0.5f : float(k) / float(nodes - 1);
    float y = y0 + (y1 - y0) * t;
    for (int j = 0; j < per_node && placed < lateral; ++j, ++placed) {
      double az = phyllotaxis_azimuth(d.phyllotaxis, 3, k, j);
      // Seen from above, a leaf at azimuth az points to the side sin(az) (spiral and
      // whorled leaves that point at or away from the viewer are foreshortened).
      float side = std::sin(float(az) + 0.5f * kPi);
      float reach = std::abs(side) < 0.2f ? 0.2f : std::abs(side);
      float sign = side < 0.0f ? -1.0f : 1.0f;
      float angle = (d.leaf_angle_deg - 12.0f * t) * kPi / 180.0f;
      ShootLeaf leaf;
      leaf.base = glm::vec2(0.0f, y);
      leaf.direction = glm::normalize(glm::vec2(sign * std::sin(angle) * reach, std::cos(angle)));
      leaf.length = len * (1.0f - 0.25f * t);
      out.push_back(leaf);
    }
  }
  return out;
}

float foliage_card_aspect(const ShootDesign& d) {
  if (d.single_leaf) return leaf_aspect(d.leaf_shape);
  float half = 0.03f;
  const float half_blade = 0.5f * leaf_aspect(d.leaf_shape);
  for (const ShootLeaf& l : shoot_leaves(d)) {
    // The blade's farthest point from the twig: its tip, or a side of its widest part.
    glm::vec2 perp(l.direction.y, -l.direction.x);
    for (float s : {0.0f, 0.5f, 1.0f})
      for (float w : {-1.0f, 1.0f})
        half = std::max(half, std::abs(l.base.x + l.length * (l.direction.x * s + perp.x * w * half_blade)));
  }
  return std::min(2.0f * (half + 0.02f), 1.6f);
}

Mesh make_foliage_card(const ShootDesign& d) {
  const float w = foliage_card_aspect(d);
  // Counter-clockwise seen from +Z: base left, base right, tip right, tip left.
  const glm::vec2 corners[4] = {{-0.5f * w, 0.0f}, {0.5f * w, 0.0f}, {0.5f * w, 1.0f}, {-0.5f * w, 1.0f}};
  Mesh card;
  for (const glm::vec2& p : corners) {
    Vertex v;
    v.position = glm::vec3(p, 0.0f);
    v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    v.uv = glm::vec2(0.5f + p.x / w, 1.0f - p.y);  // texture upright, tip at the top
    card.vertices.push_back(v);
  }
  card.indices = {0, 1, 2, 0, 2, 3};
  return card;
}

Image8 make_foliage_texture(const ShootDesign& d, uint32_t size) {
  if (d.single_leaf) return make_leaf_texture(d.leaf_shape, size);
  Image8 img;
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size * 4);
  const float w = foliage_card_aspect(d);
  const std::vector<ShootLeaf> leaves = shoot_leaves(d);
  // Needles stay at least about two texels wide on the card.
  const float stroke = d.leaf_shape == LeafShape::needles
                           ? std::max(1.0f, 3.5f / (0.022f * float(size) * std::clamp(d.leaf_length, 0.05f, 0.9f)))
                           : 1.0f;
  const float twig_width = d.leaf_shape == LeafShape::needles ? 0.6f * kTwigWidth : kTwigWidth;
  // Per-leaf tone: neighbouring leaves differ a little in age and light.
  std::vector<float> tone(leaves.size());
  for (size_t k = 0; k < leaves.size(); ++k)
    tone[k] = 0.88f + 0.24f * float(hash64(k, leaves.size(), 0x5400) % 1000u) / 1000.0f;
  // Shades of leaf_texel_class: blade, vein, midrib; the twig is darker and browner.
  const float shade[4] = {1.0f, 1.0f, 0.72f, 0.58f};
  constexpr int kSub = 4;
  for (uint32_t py = 0; py < size; ++py)
    for (uint32_t px = 0; px < size; ++px) {
      int covered = 0;
      glm::vec3 sum(0.0f);
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          float x = ((float(px) + (float(sx) + 0.5f) / kSub) / float(size) - 0.5f) * w;
          float y = 1.0f - (float(py) + (float(sy) + 0.5f) / kSub) / float(size);
          // Leaves over the twig: the first leaf that covers the point wins.
          bool hit = false;
          for (size_t k = 0; k < leaves.size() && !hit; ++k) {
            const ShootLeaf& l = leaves[k];
            glm::vec2 q = glm::vec2(x, y) - l.base;
            float ly = glm::dot(q, l.direction) / l.length;
            float lx = (q.x * l.direction.y - q.y * l.direction.x) / l.length;
            if (ly < -0.02f || ly > 1.02f) continue;
            int c = leaf_texel_class(d.leaf_shape, lx, ly, stroke);
            if (c == 0) continue;
            hit = true;
            sum += glm::vec3(shade[c] * tone[k]);
          }
          if (!hit && y >= 0.0f && y <= kTwigEnd &&
              std::abs(x) < twig_width * (1.0f - 0.66f * y / kTwigEnd)) {
            hit = true;
            sum += glm::vec3(0.62f, 0.50f, 0.38f);  // young bark: the leaf colour turns it olive-brown
          }
          if (hit) ++covered;
        }
      glm::vec3 c = covered ? sum / float(covered) : glm::vec3(1.0f);
      float mottle = 1.0f - 0.06f * float(hash64(px / 3, py / 3, 0x1eaf) % 1000u) / 1000.0f;
      uint8_t* out = &img.rgba[(size_t(py) * size + px) * 4];
      out[0] = uint8_t(std::lround(255.0f * std::clamp(c.x * mottle * 0.97f, 0.0f, 1.0f)));
      out[1] = uint8_t(std::lround(255.0f * std::clamp(c.y * mottle, 0.0f, 1.0f)));
      out[2] = uint8_t(std::lround(255.0f * std::clamp(c.z * mottle * 0.90f, 0.0f, 1.0f)));
      out[3] = uint8_t((covered * 255 + kSub * kSub / 2) / (kSub * kSub));
    }
  return img;
}

}  // namespace forest
