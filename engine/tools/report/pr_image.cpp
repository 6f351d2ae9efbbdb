#include "engine/tools/report/pr_image.h"

#include <algorithm>
#include <string>

#include "generators/core/input_error.h"

namespace forest {
namespace {

bool is_covered(const uint8_t* px, uint8_t threshold) {
  return std::max({px[0], px[1], px[2]}) >= threshold;
}

void set_rgb(uint8_t* px, uint8_t r, uint8_t g, uint8_t b) {
  px[0] = r, px[1] = g, px[2] = b, px[3] = 255;
}

}  // namespace

PrResult compare_coverage(const FrameImage& reference, const FrameImage& test, FrameImage* diff,
                          uint8_t threshold) {
  if (reference.width != test.width || reference.height != test.height)
    throw InputError("images differ in size: reference " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + ", test " + std::to_string(test.width) + "x" +
                     std::to_string(test.height));
  if (diff) {
    diff->width = reference.width;
    diff->height = reference.height;
    diff->rgba.assign(reference.rgba.size(), 255);
  }
  PrResult pr;
  const size_t pixels = size_t(reference.width) * reference.height;
  for (size_t i = 0; i < pixels; ++i) {
    bool in_ref = is_covered(&reference.rgba[i * 4], threshold);
    bool in_test = is_covered(&test.rgba[i * 4], threshold);
    uint8_t* out = diff ? &diff->rgba[i * 4] : nullptr;
    if (in_ref && in_test) {
      ++pr.tp;
      if (out) set_rgb(out, 144, 238, 144);  // light green: kept
    } else if (in_test) {
      ++pr.fp;
      if (out) set_rgb(out, 220, 40, 40);  // red: drawn only by the pruned model
    } else if (in_ref) {
      ++pr.fn;
      if (out) set_rgb(out, 0, 100, 0);  // dark green: lost by pruning
    }
  }
  return pr;
}

}  // namespace forest
