#include "engine/render/leaf_textures.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace forest {

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
      // Color averaged weighted by alpha, so transparent texels do not darken the edge;
      // alpha averaged plainly (coverage).
      float rgb[3] = {0, 0, 0}, alpha = 0, weight = 0;
      for (uint32_t dy = 0; dy < 2; ++dy)
        for (uint32_t dx = 0; dx < 2; ++dx) {
          uint32_t sx = std::min(2 * x + dx, src.width - 1), sy = std::min(2 * y + dy, src.height - 1);
          const uint8_t* p = &src.rgba[(size_t(sy) * src.width + sx) * 4];
          float w = float(p[3]) + 1.0f;
          for (int c = 0; c < 3; ++c) rgb[c] += w * float(p[c]);
          weight += w;
          alpha += float(p[3]);
        }
      uint8_t* q = &out.rgba[(size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 3; ++c) q[c] = uint8_t(std::lround(rgb[c] / weight));
      q[3] = uint8_t(std::lround(alpha / 4.0f));
    }
  return out;
}

TextureArrayData build_leaf_texture_array(const std::vector<const Image8*>& images, uint32_t size) {
  TextureArrayData data;
  data.size = size;
  data.layers = uint32_t(std::max<size_t>(images.size(), 1));
  data.mips = uint32_t(std::bit_width(size));
  for (uint32_t layer = 0; layer < data.layers; ++layer) {
    const Image8* src = layer < images.size() ? images[layer] : nullptr;
    Image8 level;
    if (src && src->width > 0 && src->height > 0 && src->rgba.size() == size_t(src->width) * src->height * 4) {
      level = resample(*src, size);
    } else {
      level.width = level.height = size;
      level.rgba.assign(size_t(size) * size * 4, 255);
    }
    for (uint32_t mip = 0; mip < data.mips; ++mip) {
      data.texels.insert(data.texels.end(), level.rgba.begin(), level.rgba.end());
      if (mip + 1 < data.mips) level = downsample(level);
    }
  }
  return data;
}

}  // namespace forest
