#include "engine/render/impostor_textures.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace forest {

Image8 downsample_by_coverage(const Image8& src, const Image8& coverage) {
  Image8 out;
  out.width = std::max(src.width / 2, 1u);
  out.height = std::max(src.height / 2, 1u);
  out.rgba.resize(size_t(out.width) * out.height * 4);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      float sum[3] = {0, 0, 0}, weight = 0;
      for (uint32_t dy = 0; dy < 2; ++dy)
        for (uint32_t dx = 0; dx < 2; ++dx) {
          size_t at = (size_t(std::min(2 * y + dy, src.height - 1)) * src.width + std::min(2 * x + dx, src.width - 1)) * 4;
          float w = float(coverage.rgba[at + 3]);
          for (int c = 0; c < 3; ++c) sum[c] += w * float(src.rgba[at + size_t(c)]);
          weight += w;
        }
      uint8_t* q = &out.rgba[(size_t(y) * out.width + x) * 4];
      for (int c = 0; c < 3; ++c) q[c] = weight > 0 ? uint8_t(std::lround(sum[c] / weight)) : 128;
      q[3] = 255;
    }
  return out;
}

ImpostorArrays build_impostor_arrays(const std::vector<const TreeModel*>& models) {
  ImpostorArrays a;
  a.layer.assign(models.size(), 0);
  std::vector<const Impostor*> baked;
  for (size_t i = 0; i < models.size(); ++i)
    if (models[i]->impostor.present()) {
      baked.push_back(&models[i]->impostor);
      a.layer[i] = uint32_t(baked.size());
    }
  const uint32_t size = baked.empty() ? 1u : uint32_t(IMPOSTOR_ATLAS_SIZE);
  // Levels down to one texel per view: IMPOSTOR_VIEW_SIZE is a power of two.
  const uint32_t mips = baked.empty() ? 1u : uint32_t(std::bit_width(uint32_t(IMPOSTOR_VIEW_SIZE)));
  for (TextureArrayData* t : {&a.albedo, &a.normals}) {
    t->size = size;
    t->layers = uint32_t(baked.size()) + 1;
    t->mips = mips;
  }
  // Layer 0: empty (transparent albedo, neutral normal), every level.
  for (uint32_t mip = 0, s = size; mip < mips; ++mip, s = std::max(s / 2, 1u)) {
    a.albedo.texels.insert(a.albedo.texels.end(), size_t(s) * s * 4, 0);
    for (size_t i = 0; i < size_t(s) * s; ++i) a.normals.texels.insert(a.normals.texels.end(), {128, 128, 128, 255});
  }
  for (const Impostor* imp : baked) {
    Image8 albedo = imp->albedo, normals = imp->normal_depth;
    for (uint32_t mip = 0; mip < mips; ++mip) {
      a.albedo.texels.insert(a.albedo.texels.end(), albedo.rgba.begin(), albedo.rgba.end());
      a.normals.texels.insert(a.normals.texels.end(), normals.rgba.begin(), normals.rgba.end());
      if (mip + 1 < mips) {
        normals = downsample_by_coverage(normals, albedo);
        albedo = downsample(albedo);
      }
    }
  }
  return a;
}

}  // namespace forest
