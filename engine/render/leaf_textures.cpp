#include "engine/render/leaf_textures.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace forest {

// The array is VK_FORMAT_R8G8B8A8_SRGB: color is averaged in linear light, not on the
// encoded bytes (which would darken every mip a little).
float srgb_to_linear(uint8_t v) {
  float c = float(v) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

uint8_t linear_to_srgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  float e = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(e * 255.0f));
}

Image8 resample(const Image8& src, uint32_t size) {
  Image8 out;
  out.width = out.height = size;
  out.rgba.resize(size_t(size) * size * 4);
  if (src.width == size && src.height == size) {
    out.rgba = src.rgba;
    return out;
  }
  auto at = [&](int x, int y, int c) {
    x = std::clamp(x, 0, int(src.width) - 1);
    y = std::clamp(y, 0, int(src.height) - 1);
    return float(src.rgba[(size_t(y) * src.width + size_t(x)) * 4 + size_t(c)]);
  };
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      float fx = (float(x) + 0.5f) * float(src.width) / float(size) - 0.5f;
      float fy = (float(y) + 0.5f) * float(src.height) / float(size) - 0.5f;
      int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
      float tx = fx - float(x0), ty = fy - float(y0);
      for (int c = 0; c < 4; ++c) {
        float v = (at(x0, y0, c) * (1 - tx) + at(x0 + 1, y0, c) * tx) * (1 - ty) +
                  (at(x0, y0 + 1, c) * (1 - tx) + at(x0 + 1, y0 + 1, c) * tx) * ty;
        out.rgba[(size_t(y) * size + x) * 4 + size_t(c)] = uint8_t(std::lround(std::clamp(v, 0.0f, 255.0f)));
      }
    }
  return out;
}

Image8 downsample(const Image8& src) {
  Image8 out;
  out.width = std::max(src.width / 2, 1u);
  out.height = std::max(src.height / 2, 1u);
  out.rgba.resize(size_t(out.width) * out.height * 4);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      // Color averaged in linear light weighted by alpha, so transparent texels (whatever
      // their RGB) barely reach the edge; alpha averaged plainly.
      float rgb[3] = {0, 0, 0}, alpha = 0, weight = 0;
      for (uint32_t dy = 0; dy < 2; ++dy)
        for (uint32_t dx = 0; dx < 2; ++dx) {
          uint32_t sx = std::min(2 * x + dx, src.width - 1), sy = std::min(2 * y + dy, src.height - 1);
          const uint8_t* p = &src.rgba[(size_t(sy) * src.width + sx) * 4];
          float w = float(p[3]) + 1.0f;
          for (int c = 0; c < 3; ++c) rgb[c] += w * srgb_to_linear(p[c]);
          weight += w;
          alpha += float(p[3]);
        }
      uint8_t* q = &out.rgba[(size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 3; ++c) q[c] = linear_to_srgb(rgb[c] / weight);
      q[3] = uint8_t(std::lround(alpha / 4.0f));
    }
  return out;
}

float alpha_coverage(const Image8& img, float scale) {
  // Castaño's estimate: 4 x 4 bilinear samples per texel, so that small levels still give a
  // fraction finer than 1 / texel count.
  constexpr int kSub = 4;
  const int w = int(img.width), h = int(img.height);
  if (w == 0 || h == 0) return 0.0f;
  auto alpha = [&](int x, int y) {
    x = std::clamp(x, 0, w - 1), y = std::clamp(y, 0, h - 1);
    return float(img.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4 + 3]);
  };
  const float cutoff = 127.5f / std::max(scale, 1e-6f);
  size_t passed = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int sy = 0; sy < kSub; ++sy)
        for (int sx = 0; sx < kSub; ++sx) {
          float fx = (float(sx) + 0.5f) / kSub - 0.5f, fy = (float(sy) + 0.5f) / kSub - 0.5f;
          int x0 = fx < 0.0f ? x - 1 : x, y0 = fy < 0.0f ? y - 1 : y;
          float tx = fx < 0.0f ? fx + 1.0f : fx, ty = fy < 0.0f ? fy + 1.0f : fy;
          float a = (alpha(x0, y0) * (1 - tx) + alpha(x0 + 1, y0) * tx) * (1 - ty) +
                    (alpha(x0, y0 + 1) * (1 - tx) + alpha(x0 + 1, y0 + 1) * tx) * ty;
          passed += a > cutoff;
        }
  return float(passed) / float(size_t(w) * size_t(h) * kSub * kSub);
}

Image8 preserve_alpha_coverage(const Image8& img, float coverage) {
  // Coverage grows with the scale: bisect for the scale that meets the target.
  float lo = 0.0f, hi = 64.0f;
  for (int i = 0; i < 24; ++i) {
    float mid = 0.5f * (lo + hi);
    (alpha_coverage(img, mid) < coverage ? lo : hi) = mid;
  }
  float scale = std::abs(alpha_coverage(img, lo) - coverage) < std::abs(alpha_coverage(img, hi) - coverage) ? lo : hi;
  // Where the level already meets the target (an opaque level: any scale above 1/2 does),
  // leave alpha alone.
  if (std::abs(alpha_coverage(img, 1.0f) - coverage) <= std::abs(alpha_coverage(img, scale) - coverage)) scale = 1.0f;
  Image8 out = img;
  for (size_t i = 3; i < out.rgba.size(); i += 4)
    out.rgba[i] = uint8_t(std::lround(std::min(float(out.rgba[i]) * scale, 255.0f)));
  return out;
}

TextureArrayData build_leaf_texture_array(const std::vector<const Image8*>& images, uint32_t size) {
  TextureArrayData data;
  data.size = size;
  data.layers = uint32_t(std::max<size_t>(images.size(), 1));
  // The chain stops at 8 x 8: below that a uniform alpha scale cannot keep the coverage of a
  // card carrying a whole shoot (its 2 x 2 and 1 x 1 levels pass all or nothing), and
  // distant crowns lost their foliage. A card smaller than 8 texels on screen samples the
  // 8 x 8 level (a little aliasing, the right coverage).
  data.mips = uint32_t(std::bit_width(size)) - std::min(3u, uint32_t(std::bit_width(size)) - 1u);
  for (uint32_t layer = 0; layer < data.layers; ++layer) {
    const Image8* src = layer < images.size() ? images[layer] : nullptr;
    Image8 level;
    if (src && src->width > 0 && src->height > 0 && src->rgba.size() == size_t(src->width) * src->height * 4) {
      level = resample(*src, size);
    } else {
      level.width = level.height = size;
      level.rgba.assign(size_t(size) * size * 4, 255);
    }
    // The box-filtered chain thins alpha-tested detail: thin needles average to alpha < 0.5
    // and vanish at distance. Each stored level has its alpha rescaled so that as much of it
    // passes the cutoff as of the full-resolution texture.
    const float coverage = alpha_coverage(level, 1.0f);
    for (uint32_t mip = 0; mip < data.mips; ++mip) {
      Image8 stored = mip == 0 ? level : preserve_alpha_coverage(level, coverage);
      data.texels.insert(data.texels.end(), stored.rgba.begin(), stored.rgba.end());
      if (mip + 1 < data.mips) level = downsample(level);
    }
  }
  return data;
}

}  // namespace forest
