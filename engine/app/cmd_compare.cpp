// forest compare: Precision/Recall/Q of a test coverage image against a reference and the
// Fig 7.1 tp/fp/fn picture — the PR-score regression check on image files.
#include <cstdio>

#include "engine/app/commands.h"
#include "engine/present/image_io.h"
#include "engine/tools/report/pr_image.h"
#include "generators/core/input_error.h"

namespace forest::app {

int run_compare(const CompareArgs& args) {
  if (!args.diff.empty()) check_output_path(args.diff, "--diff");
  FrameImage reference = read_image(args.reference);
  FrameImage test = read_image(args.test);
  if (reference.width != test.width || reference.height != test.height)
    throw InputError(args.test + ": " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                     " differs from " + args.reference + ": " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height));
  FrameImage diff;
  PrResult pr = compare_coverage(reference, test, args.diff.empty() ? nullptr : &diff, args.threshold);
  if (!args.diff.empty()) write_image(diff, args.diff);
  std::printf("P %.4f R %.4f Q %.4f (tp %llu fp %llu fn %llu)\n", pr.precision(), pr.recall(), pr.quality(),
              (unsigned long long)pr.tp, (unsigned long long)pr.fp, (unsigned long long)pr.fn);
  if (args.min_quality && pr.quality() < *args.min_quality) {
    std::fprintf(stderr, "forest: %s: Q %.4f is below --min-quality %.4f\n", args.test.c_str(), pr.quality(),
                 *args.min_quality);
    return 3;
  }
  return 0;
}

}  // namespace forest::app
