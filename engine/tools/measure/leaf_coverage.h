// Leaf coverage of a model, measured with the engine: orthographic side views of its leaves
// alone (no bark), drawn as coverage masks through the frame pipelines (FrameSettings::mask,
// FrameSettings::branches = false), the camera fitted to the leaves' bounding box. Coverage
// of a view = leaf pixels ÷ the area of the 2D convex hull of the leaf pixels: 1 for a crown
// whose silhouette is solid, near 0 for a few leaves spread thin (`forest measure`).
#pragma once
#include <cstdint>
#include <vector>

#include "engine/render/renderer.h"

namespace forest {

struct LeafCoverageOptions {
  uint32_t resolution = 512;  // pixels of each square view
  // Azimuths about the vertical axis, as orbit_camera (contact_sheet.h): 0 looks from −z
  // towards +z, 90 from +x.
  std::vector<float> azimuths_deg = {0.0f, 90.0f, 180.0f, 270.0f};
  float margin = 0.02f;    // the box's silhouette fills 1 / (1 + margin) of the frame
  bool keep_masks = false;  // return the mask images too
};

// Coverage of one mask image.
struct MaskCoverage {
  uint64_t pixels = 0;    // covered pixels (red ≥ 128: the mask is white on black)
  double hull_area = 0;   // square pixels inside the convex hull of the covered pixels' squares
  // pixels ÷ hull_area, in (0, 1] (the hull holds every covered square, and exactly them for
  // a filled rectangle); 0 for an empty mask.
  double coverage() const { return hull_area > 0.0 ? double(pixels) / hull_area : 0.0; }
};

struct ViewCoverage {
  float azimuth_deg = 0;
  MaskCoverage mask;
};

struct LeafCoverage {
  uint32_t resolution = 0;          // pixels of each square view
  std::vector<ViewCoverage> views;  // in the order of LeafCoverageOptions::azimuths_deg
  double min = 0;                   // the smallest coverage of the views
  std::vector<FrameImage> masks;    // with keep_masks, one per view
};

MaskCoverage mask_coverage(const FrameImage& mask);

// The axis-aligned box (model space) of every leaf card's corners; {0, 0} without leaves.
struct Box {
  glm::vec3 lo{0.0f}, hi{0.0f};
};
Box leaf_box(const TreeModel& model);

// A horizontal orthographic camera looking at the box's centre from `azimuth_rad` whose
// square frame holds the box's silhouette with `margin` to spare.
CameraDesc fitted_side_camera(const Box& box, float azimuth_rad, float margin);

// Renders `model`'s leaves from every azimuth (single-sampled, full detail) and measures
// each mask. A model without leaves gives coverage 0 everywhere.
LeafCoverage measure_leaf_coverage(vk::Context& ctx, const TreeModel& model, const LeafCoverageOptions& options = {});

}  // namespace forest
