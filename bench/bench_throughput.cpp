#include "bench/bench_throughput.h"

#include <cmath>

namespace forest {

namespace {

// A 1 m × 1 m vertical sheet of grid × grid quads in the x-y plane, facing −z (the camera).
TreeModel triangle_sheet(uint32_t grid) {
  TreeModel m;
  Mesh& mesh = m.branches;
  for (uint32_t y = 0; y <= grid; ++y)
    for (uint32_t x = 0; x <= grid; ++x) {
      Vertex v;
      v.position = glm::vec3(float(x) / float(grid) - 0.5f, float(y) / float(grid), 0.0f);
      v.normal = glm::vec3(0.0f, 0.0f, -1.0f);
      v.uv = glm::vec2(float(x), float(y)) / float(grid);
      mesh.vertices.push_back(v);
    }
  for (uint32_t y = 0; y < grid; ++y)
    for (uint32_t x = 0; x < grid; ++x) {
      uint32_t a = y * (grid + 1) + x, b = a + 1, c = a + grid + 1, d = c + 1;
      // Both windings of each quad face the camera side: counter-clockwise seen from −z.
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  // One tiny leaf so every buffer of the renderer has content; it adds 2 triangles per instance.
  m.leaf_card.vertices = {Vertex{{-0.005f, 0, 0}, {0, 0, -1}, {0, 0}}, Vertex{{0.005f, 0, 0}, {0, 0, -1}, {1, 0}},
                          Vertex{{0, 0.01f, 0}, {0, 0, -1}, {0.5f, 1}}};
  m.leaf_card.indices = {0, 1, 2};
  m.leaves.push_back(LeafPlacement{});
  m.bounding_sphere = glm::vec4(0.0f, 0.5f, 0.0f, 0.75f);
  return m;
}

}  // namespace

ThroughputResult measure_triangle_throughput(vk::Context& ctx, const ThroughputOptions& options) {
  Scene scene;
  uint32_t side = std::max(1u, uint32_t(std::ceil(std::sqrt(double(options.instances)))));
  scene.desc.width = options.width;
  scene.desc.height = options.height;
  scene.desc.samples = 1;
  scene.desc.lod_error_pixels = 0.0f;  // LOD0 always
  scene.desc.sky.fog_density = 0.0f;
  scene.desc.terrain.size = float(side) * 2.0f + 4.0f;
  scene.desc.terrain.resolution = 2;
  scene.desc.terrain.height = 0.0f;
  for (uint32_t i = 0; i < options.instances; ++i) {
    TreeDesc t;
    t.x = (float(i % side) - 0.5f * float(side - 1)) * 1.1f;
    t.z = float(i / side) * 0.3f;  // rows step back a little: overlapping sheets, all in view
    scene.desc.trees.push_back(t);
  }
  scene.terrain = make_terrain(scene.desc.terrain);
  scene.models.push_back(triangle_sheet(options.grid));
  scene.instances = place_trees(scene.desc, scene.terrain);

  CameraDesc camera;
  float half_width = 0.55f * float(side) + 0.5f;
  camera.fov_deg = 50.0f;
  float aspect = float(options.width) / float(options.height);
  float distance = half_width / (std::tan(glm::radians(camera.fov_deg) * 0.5f) * aspect) + 1.0f;
  camera.position = glm::vec3(0.0f, 0.5f, -distance);
  camera.target = glm::vec3(0.0f, 0.5f, 0.0f);
  camera.near = 0.05f;
  camera.far = distance + float(side) + 10.0f;

  Renderer renderer(ctx, scene, options.width, options.height, 1);
  FrameSettings settings;  // PruneMode::full: every triangle of LOD0
  renderer.render(camera, nullptr, settings);  // warm-up (pipeline caches, first-touch memory)
  ThroughputResult r;
  uint64_t index_triangles = uint64_t(scene.models[0].branches.indices.size() / 3) * scene.instances.size();
  for (uint32_t f = 0; f < options.frames; ++f) {
    FrameStats s = renderer.render(camera, nullptr, settings);
    r.draw_ms += s.draw_ms / options.frames;
    r.frame_ms += s.frame_ms / options.frames;
    r.triangles_per_frame = s.draw_pipeline.available ? s.draw_pipeline.ia_primitives
                                                      : index_triangles;
  }
  return r;
}

}  // namespace forest
