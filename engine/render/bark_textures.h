// CPU preparation of the bark texture arrays: every model's bark albedo and normal map
// (TreeModel::bark_texture, bark_normal) resampled to one square size with full mip chains.
// Layer 0 is neutral (white albedo, flat normal) for models without bark textures, whose
// colour is then their bark_color; models with identical textures (the same species and
// colour, other seeds) share a layer.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/render/leaf_textures.h"
#include "generators/model/tree_model.h"

namespace forest {

struct BarkTextureArrays {
  TextureArrayData albedo;   // sRGB RGBA8, mips box-filtered in linear light
  TextureArrayData normals;  // RGBA8 UNORM, n * 0.5 + 0.5; mips averaged and renormalized
  std::vector<uint32_t> layer;     // per model
  std::vector<uint8_t> coloured;   // per model: 1 when its albedo layer holds its colour
};

BarkTextureArrays build_bark_texture_arrays(const std::vector<const TreeModel*>& models, uint32_t size);

// Next mip level of a normal map: 2 × 2 average of the decoded normals, renormalized (a
// flat normal where they cancel).
Image8 downsample_normals(const Image8& image);

}  // namespace forest
