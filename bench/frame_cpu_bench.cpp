// Per-frame CPU cost of the renderer vs the number of tree instances (DESIGN: the frame
// loop is O(1) on the CPU in the instance count). For each count, the same model is placed
// on flat ground and F frames are rendered from a view over the forest; prints the CPU time
// per frame (frame constants + command recording + submit, excluding the wait for the GPU)
// and the GPU frame time from timestamps. Usage:
//   frame_cpu_bench [--frames F] [--counts 100,5000] [--size WxH]
// Pin the driver with VK_DRIVER_FILES and LP_NUM_THREADS on lavapipe; compare ratios only.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"
#include "generators/species/registry.h"

using namespace forest;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 30;
  uint32_t width = 320, height = 180;
  std::vector<uint32_t> counts = {100, 5000};
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--counts" && i + 1 < argc) {
      counts.clear();
      std::stringstream ss(argv[++i]);
      for (std::string c; std::getline(ss, c, ',');) counts.push_back(uint32_t(std::max(1, std::atoi(c.c_str()))));
    } else if (a == "--size" && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%ux%u", &width, &height) != 2) width = 320, height = 180;
    } else {
      std::fprintf(stderr, "usage: frame_cpu_bench [--frames F] [--counts 100,5000] [--size WxH]\n");
      return 2;
    }
  }
  vk::Context ctx;
  try {
    vk::create_context(ctx, {});
    TreeModel model = generate_from_species(std::string(FOREST_SOURCE_DIR) + "/scenes/species/broadleaf.toml", GenerateOptions{11});
    std::printf("device %s, %ux%u, %d frames per count, mode cook\n", ctx.properties.deviceName, width, height, frames);
    std::printf("%8s %8s %14s %14s %14s\n", "trees", "visible", "CPU med (ms)", "CPU min (ms)", "GPU med (ms)");
    double first_median = 0.0;
    for (uint32_t count : counts) {
      Scene s;
      s.desc.terrain.size = 1200.0f;
      s.desc.terrain.height = 0.0f;
      s.desc.terrain.resolution = 32;
      s.desc.species.resize(1);
      s.desc.placement.count = count;
      s.desc.placement.seed = 3;
      s.desc.placement.min_spacing = 2.0f;
      s.desc.placement.radius = 500.0f;
      s.desc.prune_distance = 400.0f;
      s.desc.camera.position = glm::vec3(0.0f, 40.0f, -520.0f);
      s.desc.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
      s.desc.camera.far = 1500.0f;
      s.terrain = make_terrain(s.desc.terrain);
      s.models.push_back(model);
      s.instances = place_trees(s.desc, s.terrain);
      Renderer r(ctx, s, width, height, 1);
      FrameSettings settings;
      settings.prune_mode = PruneMode::cook;
      std::vector<double> cpu, gpu;
      uint32_t visible = 0;
      r.render(s.desc.camera, nullptr, settings);  // warm-up: pipelines, first-touch memory
      for (int f = 0; f < frames; ++f) {
        FrameStats st = r.render(s.desc.camera, nullptr, settings);
        cpu.push_back(st.cpu_submit_ms);
        gpu.push_back(st.frame_ms);
        visible = st.branch_draws;
      }
      double m = median(cpu);
      if (first_median == 0.0) first_median = m;
      std::printf("%8zu %8u %14.4f %14.4f %14.2f   CPU ratio to first: %.2f\n", s.instances.size(), visible, m,
                  *std::min_element(cpu.begin(), cpu.end()), median(gpu), m / first_median);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "frame_cpu_bench: %s\n", e.what());
    vk::destroy_context(ctx);
    return 1;
  }
  vk::destroy_context(ctx);
  return 0;
}
