// Raw-throughput probe of `forest bench`: the same Renderer drawing a field of plain small
// triangles (no leaves, no pruning, LOD0 only), timed with its GPU timestamps. What the
// device can push through this engine's draw pass, the yardstick for the forest's modes.
#pragma once
#include <cstdint>

#include "engine/render/renderer.h"

namespace forest {

struct ThroughputOptions {
  uint32_t width = 640, height = 360;
  uint32_t grid = 96;        // one instance: grid × grid quads (2 triangles each)
  uint32_t instances = 64;   // instances in a square array, all in view
  uint32_t frames = 4;       // timed frames after one warm-up frame
};

struct ThroughputResult {
  uint64_t triangles_per_frame = 0;  // input-assembly primitives of the draw pass (or index count / 3)
  double draw_ms = 0.0;              // GPU draw pass, mean over the timed frames
  double frame_ms = 0.0;             // GPU frame (cull + draw + ...), mean
  double triangles_per_second() const { return draw_ms > 0 ? double(triangles_per_frame) / (draw_ms * 1e-3) : 0.0; }
};

ThroughputResult measure_triangle_throughput(vk::Context& ctx, const ThroughputOptions& options);

}  // namespace forest
