// measure_pop: flipped coverage, the largest group, and solid (2x2) groups
// against slivers.
#include <gtest/gtest.h>

#include "engine/tools/report/popping.h"
#include "tests/unit/blank_image.h"

using namespace forest;

namespace {

FrameImage blank(uint32_t w, uint32_t h) { return test::blank_image(w, h, 0); }

void set(FrameImage& img, uint32_t x, uint32_t y, uint8_t value) {
  for (int c = 0; c < 3; ++c) img.rgba[(size_t(y) * img.width + x) * 4 + c] = value;
}

}  // namespace

TEST(Popping, SliversAreGroupsButNotSolidGroups) {
  FrameImage before = blank(20, 10), after = blank(20, 10);
  for (uint32_t y = 0; y < 10; ++y) set(before, 2, y, 255), set(after, 2, y, 255);  // a trunk, unchanged
  for (uint32_t y = 0; y < 10; ++y) set(after, 3, y, 255);                          // one pixel wider: a sliver
  PopStep s = measure_pop(before, after);
  EXPECT_EQ(s.covered, 10u);
  EXPECT_EQ(s.changed, 10u);
  EXPECT_EQ(s.largest_blob, 10u);
  EXPECT_EQ(s.largest_solid_blob, 0u);
  EXPECT_DOUBLE_EQ(s.share(), 1.0);

  // A 3x3 leaf appears, and a diagonal pair elsewhere (8-connected, not solid).
  for (uint32_t y = 4; y < 7; ++y)
    for (uint32_t x = 10; x < 13; ++x) set(after, x, y, 200);
  set(after, 17, 1, 255), set(after, 18, 2, 255);
  set(after, 17, 8,
      100);  // under the coverage threshold: not covered, not flipped
  s = measure_pop(before, after);
  EXPECT_EQ(s.changed, 10u + 9u + 2u);
  EXPECT_EQ(s.largest_blob, 10u);
  EXPECT_EQ(s.largest_solid_blob, 9u);
}

TEST(Popping, IdenticalImagesFlipNothingAndSizesMustMatch) {
  FrameImage a = blank(8, 8);
  set(a, 3, 3, 255);
  PopStep s = measure_pop(a, a);
  EXPECT_EQ(s.changed, 0u);
  EXPECT_EQ(s.largest_blob, 0u);
  EXPECT_EQ(s.covered, 1u);
  EXPECT_THROW(measure_pop(a, blank(8, 9)), std::invalid_argument);
}
