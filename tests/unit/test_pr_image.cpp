// compare_coverage: tp/fp/fn counting and the Fig 7.1 colours of `forest compare`.
#include <gtest/gtest.h>

#include "engine/tools/report/pr_image.h"
#include "generators/core/input_error.h"
#include "tests/unit/blank_image.h"

using namespace forest;

namespace {

FrameImage blank(uint32_t w, uint32_t h) { return test::blank_image(w, h, 255); }

void fill(FrameImage& img, uint32_t x0, uint32_t x1, uint8_t value) {
  for (uint32_t y = 0; y < img.height; ++y)
    for (uint32_t x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) img.rgba[(size_t(y) * img.width + x) * 4 + c] = value;
}

}  // namespace

TEST(PrImage, CountsOverlapOfTwoBands) {
  // Reference covers columns [0, 6), test covers [4, 10) of a 10×3 image.
  FrameImage ref = blank(10, 3), test = blank(10, 3), diff;
  fill(ref, 0, 6, 255);
  fill(test, 4, 10, 255);
  PrResult pr = compare_coverage(ref, test, &diff);
  EXPECT_EQ(pr.tp, 2u * 3);
  EXPECT_EQ(pr.fp, 4u * 3);
  EXPECT_EQ(pr.fn, 4u * 3);
  EXPECT_DOUBLE_EQ(pr.precision(), 2.0 / 6.0);
  EXPECT_DOUBLE_EQ(pr.recall(), 2.0 / 6.0);
  // Fig 7.1 colours: dark green fn, light green tp, red fp.
  EXPECT_EQ(diff.pixel(0, 1)[0], 0);
  EXPECT_EQ(diff.pixel(0, 1)[1], 100);
  EXPECT_EQ(diff.pixel(5, 1)[1], 238);
  EXPECT_EQ(diff.pixel(9, 1)[0], 220);
  EXPECT_EQ(diff.pixel(9, 1)[1], 40);
}

TEST(PrImage, IdenticalImagesHaveQualityOne) {
  FrameImage ref = blank(8, 8);
  fill(ref, 2, 5, 200);
  PrResult pr = compare_coverage(ref, ref, nullptr);
  EXPECT_EQ(pr.fp + pr.fn, 0u);
  EXPECT_DOUBLE_EQ(pr.quality(), 1.0);
}

TEST(PrImage, ThresholdDecidesGreyEdges) {
  FrameImage ref = blank(4, 1), test = blank(4, 1);
  fill(ref, 0, 4, 255);
  fill(test, 0, 2, 127);  // under half coverage: not covered
  fill(test, 2, 4, 128);  // half coverage: covered
  PrResult pr = compare_coverage(ref, test, nullptr);
  EXPECT_EQ(pr.tp, 2u);
  EXPECT_EQ(pr.fn, 2u);
  EXPECT_EQ(compare_coverage(ref, test, nullptr, 100).tp, 4u);
}

TEST(PrImage, SizeMismatchIsAnInputError) {
  EXPECT_THROW(compare_coverage(blank(4, 4), blank(4, 5), nullptr), InputError);
}
