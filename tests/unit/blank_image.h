// Images drawn by hand in the unit tests of the image tools.
#pragma once
#include <cstdint>

#include "engine/render/renderer.h"

namespace forest::test {

// A w x h image, black, every pixel of the given alpha.
inline FrameImage blank_image(uint32_t w, uint32_t h, uint8_t alpha) {
  FrameImage img;
  img.width = w, img.height = h;
  img.rgba.assign(size_t(w) * h * 4, 0);
  for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = alpha;
  return img;
}

}  // namespace forest::test
