// Which chunks of the terrain a view can see (Terrain::chunks): the terrain is one mesh of
// up to (4096)² cells, and a view sees a part of it — the camera a wedge, each shadow cascade
// a box around its slice of the view — while lavapipe pays for every triangle it is handed,
// seen or not. A CPU loop per view over the chunks (144 for walk.toml's 384² cells), of a cost
// that does not grow with the trees.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/terrain.h"

namespace forest {

struct IndexRange {
  uint32_t first = 0, count = 0;
};

// The index ranges of the chunks whose bounds are not wholly outside one of `planes` (inward
// normals: p is inside where dot(plane.xyz, p) + plane.w >= 0), chunks next to each other in
// index order merged into one range. Conservative: a box that crosses a plane stays.
std::vector<IndexRange> visible_chunks(std::span<const TerrainChunk> chunks, std::span<const glm::vec4> planes);

}  // namespace forest
