#include "engine/tools/report/popping.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine/tools/report/pr_image.h"

namespace forest {

namespace {

// Largest 8-connected group of set pixels, by flood fill (clears `set`).
uint64_t largest_group(std::vector<uint8_t>& set, uint32_t w, uint32_t h) {
  uint64_t largest = 0;
  std::vector<uint32_t> stack;
  for (size_t seed = 0; seed < set.size(); ++seed) {
    if (!set[seed]) continue;
    uint64_t size = 0;
    set[seed] = 0;
    stack.push_back(uint32_t(seed));
    while (!stack.empty()) {
      uint32_t p = stack.back();
      stack.pop_back();
      ++size;
      int x = int(p % w), y = int(p / w);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= int(w) || ny >= int(h)) continue;
          uint32_t q = uint32_t(ny) * w + uint32_t(nx);
          if (set[q]) set[q] = 0, stack.push_back(q);
        }
    }
    largest = std::max(largest, size);
  }
  return largest;
}

}  // namespace

PopStep measure_pop(const FrameImage& before, const FrameImage& after) {
  if (before.width != after.width || before.height != after.height)
    throw std::invalid_argument("measure_pop: images of different sizes");
  const uint32_t w = before.width, h = before.height;
  auto covered = [](const FrameImage& im, size_t p) {
    const uint8_t* c = &im.rgba[p * 4];
    return std::max({c[0], c[1], c[2]}) >= kCoverageThreshold;
  };
  PopStep r;
  std::vector<uint8_t> flipped(size_t(w) * h);
  for (size_t p = 0; p < flipped.size(); ++p) {
    bool a = covered(before, p);
    r.covered += a;
    flipped[p] = a != covered(after, p);
    r.changed += flipped[p];
  }
  // Solid pixels: those of some fully flipped 2x2 square.
  std::vector<uint8_t> solid(flipped.size());
  for (uint32_t y = 0; y + 1 < h; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      size_t p = size_t(y) * w + x;
      if (flipped[p] && flipped[p + 1] && flipped[p + w] && flipped[p + w + 1])
        solid[p] = solid[p + 1] = solid[p + w] = solid[p + w + 1] = 1;
    }
  r.largest_blob = largest_group(flipped, w, h);
  r.largest_solid_blob = largest_group(solid, w, h);
  return r;
}

namespace {

// The step with the largest key(step); an empty PopStep when there is none.
template <class Key>
PopStep worst_by(const std::vector<PopStep>& steps, Key key) {
  PopStep worst;
  for (const PopStep& s : steps)
    if (key(s) > key(worst)) worst = s;
  return worst;
}

}  // namespace

PopStep PopWalk::worst_share() const { return worst_by(steps, [](const PopStep& s) { return s.share(); }); }
PopStep PopWalk::worst_blob() const { return worst_by(steps, [](const PopStep& s) { return s.largest_blob; }); }
PopStep PopWalk::worst_solid_blob() const {
  return worst_by(steps, [](const PopStep& s) { return s.largest_solid_blob; });
}
PopStep PopWalk::worst_of_motion() const { return worst_by(steps, [](const PopStep& s) { return s.of_motion(); }); }

double PopWalk::mean_share() const {
  double sum = 0.0;
  for (const PopStep& s : steps) sum += s.share();
  return steps.empty() ? 0.0 : sum / double(steps.size());
}

PopWalk measure_popping(Renderer& renderer, const std::vector<CameraDesc>& cameras, FrameSettings settings) {
  settings.mask = true;
  settings.occlusion = false;
  PopWalk walk;
  FrameImage now, lod_moved, previous;
  for (size_t t = 0; t + 1 < cameras.size(); ++t) {
    settings.lod_camera = cameras[t].position;
    renderer.render(cameras[t], &now, settings);
    if (t > 0) walk.steps.back().moved = measure_pop(previous, now).changed;
    settings.lod_camera = cameras[t + 1].position;
    renderer.render(cameras[t], &lod_moved, settings);
    walk.steps.push_back(measure_pop(now, lod_moved));
    std::swap(previous, now);
  }
  return walk;
}

}  // namespace forest
