// CPU preparation of the leaf texture array: every model's leaf texture resampled to one
// square size with its mip chain down to 8 x 8, layer-major: a box filter (color in linear light,
// weighted by alpha) whose stored levels have alpha rescaled to keep the alpha-test coverage
// of the full-resolution level (I. Castaño, "Computing alpha mipmaps", 2010).
#pragma once
#include <cstdint>
#include <vector>

#include "generators/model/tree_model.h"

namespace forest {

struct TextureArrayData {
  uint32_t size = 0, layers = 0, mips = 0;
  std::vector<uint8_t> texels;  // layer-major, each layer mips 0..mips-1, RGBA8
};

// An empty Image8 becomes an opaque white layer (untextured leaf cards stay solid).
TextureArrayData build_leaf_texture_array(const std::vector<const Image8*>& images, uint32_t size);

// The sRGB transfer function: an 8-bit encoded value to linear light in [0, 1], and back
// (clamped, rounded).
float srgb_to_linear(uint8_t v);
uint8_t linear_to_srgb(float c);

// Bilinear resample of an RGBA8 image to size x size.
Image8 resample(const Image8& image, uint32_t size);
// Next mip level (half size, 2x2 box filter; RGB averaged in linear light weighted by alpha).
Image8 downsample(const Image8& image);

// Fraction of the image whose alpha × scale passes the 0.5 cutoff (bilinear, 4 x 4 samples
// per texel).
float alpha_coverage(const Image8& image, float scale);
// The image with alpha scaled so that alpha_coverage(result, 1) is as close to `coverage` as
// a uniform scale allows.
Image8 preserve_alpha_coverage(const Image8& image, float coverage);

}  // namespace forest
