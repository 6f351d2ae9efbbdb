#include "engine/render/terrain_cull.h"

namespace forest {

std::vector<IndexRange> visible_chunks(std::span<const TerrainChunk> chunks, std::span<const glm::vec4> planes) {
  std::vector<IndexRange> out;
  for (const TerrainChunk& c : chunks) {
    bool inside = true;
    for (const glm::vec4& p : planes) {
      // The corner farthest along the plane's normal: if even it is outside, the box is.
      const glm::vec3 corner(p.x >= 0.0f ? c.max.x : c.min.x, p.y >= 0.0f ? c.max.y : c.min.y,
                             p.z >= 0.0f ? c.max.z : c.min.z);
      if (glm::dot(glm::vec3(p), corner) + p.w < 0.0f) {
        inside = false;
        break;
      }
    }
    if (!inside) continue;
    if (!out.empty() && out.back().first + out.back().count == c.first_index)
      out.back().count += c.index_count;
    else
      out.push_back({c.first_index, c.index_count});
  }
  return out;
}

}  // namespace forest
