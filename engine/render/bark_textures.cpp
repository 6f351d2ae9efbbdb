#include "engine/render/bark_textures.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include <glm/glm.hpp>

namespace forest {

namespace {

bool usable(const Image8& img) {
  return img.width > 0 && img.height > 0 && img.rgba.size() == size_t(img.width) * img.height * 4;
}

Image8 solid(uint32_t size, uint8_t r, uint8_t g, uint8_t b) {
  Image8 img;
  img.width = img.height = size;
  img.rgba.resize(size_t(size) * size * 4);
  for (size_t i = 0; i < img.rgba.size(); i += 4) img.rgba[i] = r, img.rgba[i + 1] = g, img.rgba[i + 2] = b, img.rgba[i + 3] = 255;
  return img;
}

glm::vec3 decode(const uint8_t* p) { return glm::vec3(p[0], p[1], p[2]) / 127.5f - 1.0f; }

void encode(glm::vec3 n, uint8_t* q) {
  const float len = glm::length(n);
  n = len > 1e-6f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  for (int c = 0; c < 3; ++c) q[c] = uint8_t(std::lround(std::clamp(n[c] * 0.5f + 0.5f, 0.0f, 1.0f) * 255.0f));
  q[3] = 255;
}

// Bilinear resampling mixes encoded normals; renormalize them.
Image8 resample_normals(const Image8& img, uint32_t size) {
  if (img.width == size && img.height == size) return img;
  Image8 out = resample(img, size);
  for (size_t i = 0; i < out.rgba.size(); i += 4) encode(decode(&out.rgba[i]), &out.rgba[i]);
  return out;
}

void append_mips(TextureArrayData& data, Image8 level, Image8 (*next)(const Image8&)) {
  for (uint32_t mip = 0; mip < data.mips; ++mip) {
    data.texels.insert(data.texels.end(), level.rgba.begin(), level.rgba.end());
    if (mip + 1 < data.mips) level = next(level);
  }
}

}  // namespace

Image8 downsample_normals(const Image8& src) {
  Image8 out;
  out.width = std::max(src.width / 2, 1u);
  out.height = std::max(src.height / 2, 1u);
  out.rgba.resize(size_t(out.width) * out.height * 4);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      glm::vec3 sum(0.0f);
      for (uint32_t dy = 0; dy < 2; ++dy)
        for (uint32_t dx = 0; dx < 2; ++dx) {
          uint32_t sx = std::min(2 * x + dx, src.width - 1), sy = std::min(2 * y + dy, src.height - 1);
          sum += decode(&src.rgba[(size_t(sy) * src.width + sx) * 4]);
        }
      encode(sum, &out.rgba[(size_t(y) * out.width + x) * 4]);
    }
  return out;
}

BarkTextureArrays build_bark_texture_arrays(const std::vector<const TreeModel*>& models, uint32_t size) {
  BarkTextureArrays out;
  const uint32_t mips = uint32_t(std::bit_width(size));
  out.albedo.size = out.normals.size = size;
  out.albedo.mips = out.normals.mips = mips;
  // Layer 0: white albedo (the model's bark_color alone) and the flat normal (0, 0, 1).
  std::vector<std::pair<const Image8*, const Image8*>> layers{{nullptr, nullptr}};
  append_mips(out.albedo, solid(size, 255, 255, 255), downsample);
  append_mips(out.normals, solid(size, 128, 128, 255), downsample_normals);
  for (const TreeModel* m : models) {
    const Image8* albedo = usable(m->bark_texture) ? &m->bark_texture : nullptr;
    const Image8* normal = usable(m->bark_normal) ? &m->bark_normal : nullptr;
    out.coloured.push_back(albedo != nullptr);
    if (!albedo && !normal) {
      out.layer.push_back(0);
      continue;
    }
    auto same = [](const Image8* a, const Image8* b) {
      return a == b || (a && b && a->width == b->width && a->height == b->height && a->rgba == b->rgba);
    };
    auto it = std::find_if(layers.begin() + 1, layers.end(),
                           [&](const auto& l) { return same(l.first, albedo) && same(l.second, normal); });
    if (it != layers.end()) {
      out.layer.push_back(uint32_t(it - layers.begin()));
      continue;
    }
    out.layer.push_back(uint32_t(layers.size()));
    layers.emplace_back(albedo, normal);
    append_mips(out.albedo, albedo ? resample(*albedo, size) : solid(size, 255, 255, 255), downsample);
    append_mips(out.normals, normal ? resample_normals(*normal, size) : solid(size, 128, 128, 255), downsample_normals);
  }
  out.albedo.layers = out.normals.layers = uint32_t(layers.size());
  return out;
}

}  // namespace forest
