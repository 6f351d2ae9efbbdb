// Occlusion feedback benchmark (Neubert 2012 §7.4): leaves and triangles that depth-buffer
// occlusion saves along a walkthrough of a generated forest, and the GPU time of the depth
// pyramid + occlusion test as a fraction of the frame.
//
//   build/occlusion_bench [--trees N] [--frames N] [--width W --height H] [--mode cook|full]
//
// The walkthrough is a list of camera poses at eye height through the forest (0.6 m and
// under 2 degrees per frame: coherent motion, never a camera cut). The path is flown twice,
// occlusion off then on; every number is a sum or mean over the frames of one run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "engine/render/renderer.h"
#include "engine/scene/scene.h"

using namespace forest;

namespace {

struct Totals {
  double leaves = 0, triangles = 0, saved_leaves = 0, saved_triangles = 0, occluded = 0, visible = 0;
  double frame_ms = 0, cull_ms = 0, pyramid_ms = 0;
};

std::vector<CameraDesc> walkthrough(uint32_t frames) {
  std::vector<CameraDesc> path;
  for (uint32_t i = 0; i < frames; ++i) {
    float t = float(i);
    CameraDesc c;
    c.position = {6.0f * std::sin(t * 0.02f), 2.0f, -60.0f + 0.6f * t};
    float yaw = 0.35f * std::sin(t * 0.05f);  // looks left and right while walking
    c.target = c.position + glm::vec3(std::sin(yaw), -0.02f, std::cos(yaw)) * 10.0f;
    c.fov_deg = 60.0f;
    c.near = 0.1f;
    c.far = 400.0f;
    path.push_back(c);
  }
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  uint32_t trees = 3000, frames = 24, width = 480, height = 270;
  std::string mode = "cook";
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i];
    uint32_t v = uint32_t(std::strtoul(argv[i + 1], nullptr, 10));
    if (a == "--trees") trees = v;
    else if (a == "--frames") frames = v;
    else if (a == "--width") width = v;
    else if (a == "--height") height = v;
    else if (a == "--mode") mode = argv[i + 1];
    else {
      std::fprintf(stderr, "occlusion_bench: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  std::string text = "[render]\nsamples = 1\nmode = \"" + mode + "\"\nprune_distance = 200\n"
                     "[terrain]\nsize = 400\nresolution = 64\nheight = 6\nseed = 2\n"
                     "[[species]]\npreset = \"species/broadleaf.toml\"\nseed = 11\n"
                     "[[species]]\npreset = \"species/conifer.toml\"\nseed = 5\n"
                     "[placement]\ncount = " + std::to_string(trees) + "\nseed = 3\nmin_spacing = 3.5\nradius = 150\n";
  SceneDesc desc = parse_scene_text(text, "occlusion_bench.toml", std::string(FOREST_SOURCE_DIR) + "/scenes");
  Scene scene = build_scene(desc);
  vk::Context ctx;
  vk::create_context(ctx, {});
  std::vector<CameraDesc> path = walkthrough(frames);
  for (const TreeModel& m : scene.models)
    if (m.leaf_card.indices.size() != scene.models[0].leaf_card.indices.size())
      std::fprintf(stderr, "occlusion_bench: leaf cards differ in triangles; triangle totals use species 0's\n");
  Totals off, on;
  {
    Renderer r(ctx, scene, width, height, 1);
    for (bool occlusion : {false, true}) {
      FrameSettings fs = scene_frame_settings(desc);
      fs.occlusion = occlusion;
      Totals& t = occlusion ? on : off;
      for (size_t f = 0; f < path.size(); ++f) {
        FrameStats s = r.render(path[f], nullptr, fs);
        if (f == 0) continue;  // the first frame of a run has no previous depth (a cut)
        // Both species' leaf cards have this many triangles (checked below).
        uint32_t card_triangles = uint32_t(scene.models[0].leaf_card.indices.size() / 3);
        t.leaves += s.leaves_drawn;
        t.triangles += double(s.branch_triangles) + double(s.leaves_drawn) * card_triangles;
        t.saved_leaves += s.leaves_saved;
        t.saved_triangles += s.triangles_saved;
        t.occluded += s.occluded_instances;
        t.visible += s.branch_draws;
        t.frame_ms += s.frame_ms;
        t.cull_ms += s.cull_ms;
        t.pyramid_ms += s.pyramid_ms;
      }
    }
  }
  const double n = double(path.size() - 1);
  std::printf("occlusion_bench: %u trees (%zu placed), %ux%u, mode %s, %u frames (first of each run skipped), %s\n",
              trees, scene.instances.size(), width, height, mode.c_str(), frames, ctx.properties.deviceName);
  std::printf("                       occlusion off   occlusion on\n");
  std::printf("leaves drawn / frame   %13.0f  %13.0f  (saved %.1f %%)\n", off.leaves / n, on.leaves / n,
              100.0 * (1.0 - on.leaves / off.leaves));
  std::printf("triangles / frame      %13.0f  %13.0f  (saved %.1f %%)\n", off.triangles / n, on.triangles / n,
              100.0 * (1.0 - on.triangles / off.triangles));
  std::printf("trees drawn / frame    %13.1f  %13.1f  (culled by occlusion %.1f / frame)\n", off.visible / n,
              on.visible / n, on.occluded / n);
  std::printf("GPU frame ms           %13.2f  %13.2f\n", off.frame_ms / n, on.frame_ms / n);
  std::printf("GPU cull ms            %13.3f  %13.3f\n", off.cull_ms / n, on.cull_ms / n);
  std::printf("GPU pyramid ms         %13s  %13.3f\n", "-", on.pyramid_ms / n);
  // The occlusion test runs inside the cull pass: count that whole pass (an upper bound), and
  // its growth over the pass without occlusion (timestamps on a loaded machine are noisy).
  std::printf("pyramid + cull pass: %.2f %% of the frame with occlusion on (pyramid + cull growth: %.2f %%)\n",
              100.0 * (on.pyramid_ms + on.cull_ms) / on.frame_ms,
              100.0 * (on.pyramid_ms + std::max(0.0, on.cull_ms - off.cull_ms)) / on.frame_ms);
  std::printf("counted by the GPU: %.0f leaves, %.0f triangles saved / frame\n", on.saved_leaves / n,
              on.saved_triangles / n);
  int code = ctx.validation_messages > 0 ? 1 : 0;
  vk::destroy_context(ctx);
  return code;
}
