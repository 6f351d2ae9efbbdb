// Popping: how much of the picture changes at once when only the detail levels
// change.
//
// Moving the camera changes the picture anyway; what shows as a pop is a change
// that the motion does not explain. So each step of a walk is rendered twice
// from the same view: with the LODs and λ chosen where the camera is, and with
// those chosen where it will be one frame later (FrameSettings::lod_camera).
// The pixels that differ are exactly what the LOD change alone does to that
// frame — leaves leaving or shrinking, branch levels switching. Coverage images
// (mask view) are compared, as for Precision/Recall.
#pragma once
#include <cstdint>
#include <vector>

#include "engine/render/renderer.h"

namespace forest {

struct PopStep {
  uint64_t covered = 0;       // tree pixels in the frame before the LOD step
  uint64_t changed = 0;       // pixels whose coverage flipped with the LOD step alone
  uint64_t largest_blob = 0;  // largest 8-connected group of flipped pixels
  // The same over the pixels of fully flipped 2x2 squares: a group that is more
  // than a 1-pixel sliver (an edge moved by a pixel) — a piece of leaf or
  // branch appearing at once.
  uint64_t largest_solid_blob = 0;
  uint64_t moved = 0;  // pixels the whole step flips: motion and LOD (0 for the last step)
  double share() const { return covered ? double(changed) / double(covered) : 0.0; }
  // The LOD step's flips against everything the frame step flips: what motion
  // does not mask.
  double of_motion() const { return moved ? double(changed) / double(moved) : 0.0; }
};

// Flipped-coverage pixels between two coverage images of one size.
PopStep measure_pop(const FrameImage& before, const FrameImage& after);

struct PopWalk {
  std::vector<PopStep> steps;
  PopStep worst_share() const;  // the step with the largest changed share
  PopStep worst_blob() const;   // the step with the largest blob
  PopStep worst_solid_blob() const;
  PopStep worst_of_motion() const;  // the step whose flips are the largest part of the motion's
  double mean_share() const;
};

// Walks `cameras` (consecutive frames) with `settings` (occlusion off: it is
// measured per frame, not per LOD step) and measures each step's pop and the
// flips of the whole step.
PopWalk measure_popping(Renderer& renderer, const std::vector<CameraDesc>& cameras, FrameSettings settings);

}  // namespace forest
