#include "engine/tools/measure/leaf_coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/tools/gallery/contact_sheet.h"
#include "generators/core/hull_2d.h"
#include "generators/mesh/mesher.h"

namespace forest {

namespace {

// Pixel corners: integer points, so the hull's decisions are exact.
using Point = glm::i64vec2;

}  // namespace

MaskCoverage mask_coverage(const FrameImage& mask) {
  MaskCoverage m;
  // Only a row's leftmost and rightmost covered squares can hold hull corners.
  std::vector<Point> corners;
  for (uint32_t y = 0; y < mask.height; ++y) {
    int64_t first = -1, last = -1;
    for (uint32_t x = 0; x < mask.width; ++x)
      if (mask.pixel(x, y)[0] >= 128) {
        ++m.pixels;
        if (first < 0) first = x;
        last = x;
      }
    if (first < 0) continue;
    for (int64_t dy : {0, 1}) corners.push_back({first, y + dy}), corners.push_back({last + 1, y + dy});
  }
  std::vector<Point> h = convex_hull_2d(std::move(corners));
  int64_t twice = 0;  // shoelace
  for (size_t i = 0; i < h.size(); ++i) {
    Point a = h[i], b = h[(i + 1) % h.size()];
    twice += a.x * b.y - b.x * a.y;
  }
  m.hull_area = double(std::abs(twice)) * 0.5;
  return m;
}

Box leaf_box(const TreeModel& model) {
  Box b;
  if (model.leaves.empty() || model.leaf_card.vertices.empty()) return b;
  b.lo = glm::vec3(std::numeric_limits<float>::max());
  b.hi = -b.lo;
  for (const LeafPlacement& l : model.leaves)
    for (const Vertex& v : model.leaf_card.vertices) {
      glm::vec3 p = leaf_to_model(l, v.position);
      b.lo = glm::min(b.lo, p), b.hi = glm::max(b.hi, p);
    }
  return b;
}

CameraDesc fitted_side_camera(const Box& box, float azimuth_rad, float margin) {
  const glm::vec3 center = 0.5f * (box.lo + box.hi), half = glm::max(0.5f * (box.hi - box.lo), glm::vec3(1e-3f));
  const float reach = glm::length(half);  // the box lies within this of its centre
  // orbit_camera's convention at elevation 0; the view's right axis is horizontal, so the
  // box's silhouette is |right.x| hx + |right.z| hz wide and hy tall.
  const glm::vec3 back(std::sin(azimuth_rad), 0.0f, -std::cos(azimuth_rad));
  const glm::vec3 right = glm::normalize(glm::cross(-back, glm::vec3(0.0f, 1.0f, 0.0f)));
  const float half_width = std::abs(right.x) * half.x + std::abs(right.z) * half.z;
  CameraDesc cam;
  const float distance = 2.0f * reach + 1.0f;
  cam.target = center;
  cam.position = center + distance * back;
  cam.near = 0.5f * (distance - reach);
  cam.far = distance + 2.0f * reach;
  cam.ortho_height = 2.0f * std::max(half.y, half_width) * (1.0f + margin);
  return cam;
}

LeafCoverage measure_leaf_coverage(vk::Context& ctx, const TreeModel& model, const LeafCoverageOptions& options) {
  LeafCoverage out;
  out.resolution = options.resolution;
  const Box local = leaf_box(model);
  Scene scene = make_model_scene(model, options.resolution, 1);
  // Every leaf at its full size: the transition band would shrink the last leaves of the
  // prefix even at full detail (λ = 1).
  scene.desc.transition = 0.0f;
  // The box where the scene put the model (hand-placed: no yaw).
  const glm::vec4 placed = scene.instances.at(0).position_scale;
  const Box box{local.lo * placed.w + glm::vec3(placed), local.hi * placed.w + glm::vec3(placed)};
  Renderer renderer(ctx, scene, options.resolution, options.resolution, 1);
  FrameSettings settings;
  settings.mask = true;
  settings.branches = false;
  out.min = options.azimuths_deg.empty() ? 0.0 : 1.0;
  for (float azimuth : options.azimuths_deg) {
    FrameImage image;
    renderer.render(fitted_side_camera(box, glm::radians(azimuth), options.margin), &image, settings);
    ViewCoverage v{azimuth, mask_coverage(image)};
    out.min = std::min(out.min, v.mask.coverage());
    out.views.push_back(v);
    if (options.keep_masks) out.masks.push_back(std::move(image));
  }
  return out;
}

}  // namespace forest
