// Precision/Recall of two coverage images on the CPU (Neubert 2012 §7.2.2, Fig 7.1): what
// `forest compare` and the PR regression tests use on PNG files.
#pragma once
#include "engine/render/renderer.h"

namespace forest {

// A pixel is covered when its brightest channel reaches `threshold` (0..255): coverage
// images (`[render] view = "mask"`) are white trees on black, with grey MSAA edges that
// count as covered from half coverage up.
constexpr uint8_t kCoverageThreshold = 128;

// tp/fp/fn of `test` against `reference`; both must have the same size (InputError
// otherwise, naming both sizes). When `diff` is given it receives the Fig 7.1 picture:
// true positives light green, false positives red, false negatives dark green, the rest white.
PrResult compare_coverage(const FrameImage& reference, const FrameImage& test, FrameImage* diff,
                          uint8_t threshold = kCoverageThreshold);

}  // namespace forest
