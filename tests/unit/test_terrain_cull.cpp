// The terrain by chunks (Terrain::chunks) and the chunks a view draws (engine/render/
// terrain_cull.h): the chunks tile the mesh's indices, their bounds hold their triangles, and
// culling keeps every triangle a view can see while dropping most of a large terrain.
#include <gtest/gtest.h>

#include <span>

#include "engine/render/shadow_cascades.h"
#include "engine/render/terrain_cull.h"
#include "engine/scene/camera.h"

using namespace forest;

namespace {

Terrain hills(uint32_t resolution) {
  TerrainDesc d;
  d.size = 1000.0f;
  d.resolution = resolution;
  d.height = 80.0f;
  d.feature_size = 300.0f;
  d.seed = 5;
  return make_terrain(d);
}

bool inside(std::span<const glm::vec4> planes, glm::vec3 p) {
  for (const glm::vec4& plane : planes)
    if (glm::dot(glm::vec3(plane), p) + plane.w <= 0.0f) return false;
  return true;
}

// Whether index position `first` of a triangle is in one of the ranges.
bool drawn(const std::vector<IndexRange>& ranges, uint32_t first) {
  for (const IndexRange& r : ranges)
    if (first >= r.first && first < r.first + r.count) return true;
  return false;
}

// Every triangle with a corner inside the planes is drawn; returns the share of triangles drawn.
double check_conservative(const Terrain& t, const Mesh& m, std::span<const glm::vec4> planes) {
  std::vector<IndexRange> ranges = visible_chunks(t.chunks(), planes);
  uint64_t count = 0;
  for (size_t k = 0; k < ranges.size(); ++k) {
    count += ranges[k].count;
    if (k > 0) {
      EXPECT_GT(ranges[k].first, ranges[k - 1].first + ranges[k - 1].count) << "adjacent ranges not merged";
    }
  }
  for (uint32_t i = 0; i < m.indices.size(); i += 3) {
    bool seen = false;
    for (uint32_t v = 0; v < 3; ++v) seen = seen || inside(planes, m.vertices[m.indices[i + v]].position);
    if (seen) {
      EXPECT_TRUE(drawn(ranges, i)) << "triangle " << i / 3 << " has a corner in view but is not drawn";
    }
  }
  return double(count) / double(m.indices.size());
}

}  // namespace

TEST(TerrainCull, ChunksTileTheMeshAndBoundTheirTriangles) {
  Terrain t = hills(72);  // 32 + 32 + 8 cells a side: edge chunks are smaller
  Mesh m = t.mesh();
  std::vector<TerrainChunk> chunks = t.chunks();
  ASSERT_EQ(chunks.size(), 9u);
  uint32_t next = 0;
  for (const TerrainChunk& c : chunks) {
    EXPECT_EQ(c.first_index, next);
    next += c.index_count;
    for (uint32_t i = c.first_index; i < c.first_index + c.index_count; ++i) {
      glm::vec3 p = m.vertices[m.indices[i]].position;
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, c.min)) && glm::all(glm::lessThanEqual(p, c.max)))
          << "index " << i << " lies outside its chunk's bounds";
    }
  }
  EXPECT_EQ(next, m.indices.size());
  EXPECT_EQ(chunks[8].index_count, 8u * 8u * 6u);
}

TEST(TerrainCull, TheCameraDrawsWhatItSeesAndLittleElse) {
  Terrain t = hills(256);
  Mesh m = t.mesh();
  for (glm::vec3 forward : {glm::vec3(1, -0.1f, 0.3f), glm::vec3(-0.2f, -0.6f, -1), glm::vec3(0, -1, 0.01f)}) {
    CameraDesc c;
    c.position = {40.0f, t.height_at(40.0f, -60.0f) + 15.0f, -60.0f};
    c.target = c.position + forward;
    c.fov_deg = 60.0f;
    CameraMatrices cm = camera_matrices(c, 16.0f / 9.0f);
    const double share = check_conservative(t, m, std::span(cm.frustum).first(5));
    EXPECT_GT(share, 0.0);
    EXPECT_LT(share, 0.5) << "a 60° view from inside the terrain sees far less than half of it";
  }
}

TEST(TerrainCull, EachCascadeDrawsTheTerrainAroundItsSlice) {
  Terrain t = hills(256);
  Mesh m = t.mesh();
  CameraDesc c;
  c.position = {0.0f, t.height_at(0.0f, 0.0f) + 8.0f, 0.0f};
  c.target = c.position + glm::vec3(0.3f, -0.2f, 1.0f);
  c.fov_deg = 60.0f;
  const ShadowBounds bounds{{-500.0f, -40.0f, -500.0f}, {500.0f, 40.0f, 500.0f}};
  ShadowCascades sc = compute_shadow_cascades(c, 16.0f / 9.0f, glm::normalize(glm::vec3(0.45f, 0.5f, -0.5f)), 250.0f,
                                              1024, bounds);
  for (const ShadowCascade& cascade : sc.cascades)
    EXPECT_LT(check_conservative(t, m, std::span(cascade.planes).first(4)), 0.5);
}
