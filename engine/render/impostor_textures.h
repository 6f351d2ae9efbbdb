// CPU preparation of the impostor atlas arrays (impostor_pass.h): one layer per model that has
// an impostor (layer 0 stays empty: Model.impostor_layer 0 means none), each with its mip chain
// down to one texel per view (IMPOSTOR_GRID²), so that no level mixes two views. Albedo is
// averaged in linear light weighted by coverage (leaf_textures.h's downsample), the normal and
// height weighted by coverage too, so empty texels never pull a view's edge toward them.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/render/leaf_textures.h"
#include "generators/model/tree_model.h"

namespace forest {

struct ImpostorArrays {
  TextureArrayData albedo;   // VK_FORMAT_R8G8B8A8_SRGB
  TextureArrayData normals;  // VK_FORMAT_R8G8B8A8_UNORM
  std::vector<uint32_t> layer;  // per model: its layer, 0 for none
};

// Without any impostor: one empty 1 × 1 layer in each array.
ImpostorArrays build_impostor_arrays(const std::vector<const TreeModel*>& models);

// The next mip level of a normal-and-height atlas, each 2 × 2 block averaged with the weights
// of the albedo level's coverage (`coverage`, the same size); empty blocks stay neutral.
Image8 downsample_by_coverage(const Image8& normals, const Image8& coverage);

}  // namespace forest
