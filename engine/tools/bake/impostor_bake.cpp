#include "engine/tools/bake/impostor_bake.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <chrono>
#include <cmath>

#include "engine/render/leaf_textures.h"
#include "engine/render/renderer.h"
#include "engine/tools/bake/pr_bake.h"
#include "engine/tools/gallery/contact_sheet.h"
#include "impostor_math.h"

namespace forest {

namespace {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point t0) { return std::chrono::duration<double>(clock::now() - t0).count(); }

constexpr uint32_t kBakeSamples = 4;          // MSAA of the view renders: soft, unaliased coverage
constexpr float kBakeLodErrorPixels = 0.5f;   // bark LOD of a view: half a pixel of error
constexpr uint32_t kNeutralTint = 0x80808080u;  // unpack_tint: 1 in every channel
// A baked model's views draw the leaves its own tables say keep this Q at the view's size
// (PRUNE_TARGET): the views look the same, at a fraction of the leaves.
constexpr float kViewQuality = 0.98f;


// The model alone, unrotated at the origin with scale 1, so that world space is model space.
Scene bake_scene(const TreeModel& model) {
  Scene scene = make_model_scene(model, IMPOSTOR_VIEW_SIZE, kBakeSamples);
  scene.desc.lod_error_pixels = kBakeLodErrorPixels;
  scene.instances = {gpu::Instance{glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec2(1.0f, 0.0f), 0u, kNeutralTint}};
  return scene;
}

// View (i, j): orthographic, the bounding sphere filling the frame, from direction d.
CameraDesc view_camera(glm::vec4 sphere, glm::vec3 d) {
  const float r = std::max(sphere.w, 1e-3f);
  CameraDesc cam;
  cam.target = glm::vec3(sphere);
  cam.position = cam.target + d * (2.0f * r);
  cam.ortho_height = 2.0f * r;
  cam.near = 0.5f * r;
  cam.far = 4.0f * r;
  return cam;
}

// One view's three renders into cell (i, j) of both atlases. The renders are resolved
// against black, so colour and normal are premultiplied by the coverage c: divided out here.
void store_view(const FrameImage& mask, const FrameImage& albedo, const FrameImage& normal, uint32_t i, uint32_t j,
                Impostor& out) {
  for (uint32_t y = 0; y < IMPOSTOR_VIEW_SIZE; ++y)
    for (uint32_t x = 0; x < IMPOSTOR_VIEW_SIZE; ++x) {
      size_t at = (size_t(j * IMPOSTOR_VIEW_SIZE + y) * IMPOSTOR_ATLAS_SIZE + i * IMPOSTOR_VIEW_SIZE + x) * 4;
      float c = srgb_to_linear(mask.pixel(x, y)[0]);
      uint8_t* a = &out.albedo.rgba[at];
      uint8_t* n = &out.normal_depth.rgba[at];
      n[3] = 255;
      if (c < 1.0f / 255.0f) {  // empty: no colour, a neutral normal, the height of the centre
        a[0] = a[1] = a[2] = a[3] = 0;
        n[0] = n[1] = n[2] = 128;
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        a[k] = linear_to_srgb(srgb_to_linear(albedo.pixel(x, y)[k]) / c);
        n[k] = linear_to_srgb(srgb_to_linear(normal.pixel(x, y)[k]) / c);
      }
      a[3] = uint8_t(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
    }
}

}  // namespace

Impostor bake_impostor_atlases(vk::Context& ctx, const TreeModel& model, ImpostorBakeStats* stats) {
  auto t0 = clock::now();
  Scene scene = bake_scene(model);
  Renderer renderer(ctx, scene, IMPOSTOR_VIEW_SIZE, IMPOSTOR_VIEW_SIZE, kBakeSamples);
  Impostor out;
  for (Image8* img : {&out.albedo, &out.normal_depth}) {
    img->width = img->height = IMPOSTOR_ATLAS_SIZE;
    img->rgba.assign(size_t(IMPOSTOR_ATLAS_SIZE) * IMPOSTOR_ATLAS_SIZE * 4, 0);
  }
  const float r = std::max(model.bounding_sphere.w, 1e-3f);
  for (uint32_t j = 0; j < IMPOSTOR_GRID; ++j)
    for (uint32_t i = 0; i < IMPOSTOR_GRID; ++i) {
      CameraDesc cam = view_camera(model.bounding_sphere, impostor::impostor_view_direction(i, j));
      FrameSettings s;
      if (model.bake.pr_tables) {
        s.prune_mode = PruneMode::target;
        s.quality = kViewQuality;
      }
      s.mask = true;
      FrameImage mask, albedo, normal;
      renderer.render(cam, &mask, s);
      s.mask = false;
      s.impostor_bake = ImpostorBake::albedo;
      renderer.render(cam, &albedo, s);
      s.impostor_bake = ImpostorBake::normal;
      s.impostor_heights = glm::vec2(2.0f * r, 1.0f / (2.0f * r));  // the centre is 2r from the camera
      renderer.render(cam, &normal, s);
      store_view(mask, albedo, normal, i, j, out);
      if (stats) stats->renders += 3;
    }
  if (stats) stats->atlas_seconds += seconds_since(t0);
  return out;
}

ImpostorQuality measure_impostor_quality(vk::Context& ctx, const TreeModel& model, uint32_t views, uint32_t size0,
                                         ImpostorBakeStats* stats) {
  auto t0 = clock::now();
  const uint32_t resolution = pr_render_resolution(size0);
  Scene scene = make_model_scene(model, resolution, 1);
  Renderer renderer(ctx, scene, resolution, resolution, 1);
  FrameSettings impostor;
  impostor.impostors = ImpostorMode::always;
  constexpr size_t kCutoffs = std::size(kImpostorCutoffs);
  std::array<PrSizes, kCutoffs> pr{};
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const uint32_t size = uint32_t(std::lround(pr_size(float(size0), b)));
    for (const CameraDesc& cam : pr_views(model.bounding_sphere, views, std::max(size, 1u), resolution)) {
      renderer.render_reference(cam, FrameSettings{});
      for (size_t c = 0; c < kCutoffs; ++c) {
        impostor.impostor_cutoff = kImpostorCutoffs[c];
        pr[c][b] += renderer.compare_with_reference(cam, impostor);
      }
      if (stats) stats->renders += 1 + kCutoffs;
    }
  }
  ImpostorQuality out;
  double best = -1.0;
  for (size_t c = 0; c < kCutoffs; ++c) {
    double mean = 0.0;
    for (const PrResult& r : pr[c]) mean += r.quality() / PR_SIZES;
    if (mean <= best) continue;
    best = mean;
    out.cutoff = kImpostorCutoffs[c];
    out.q.clear();
    for (const PrResult& r : pr[c]) out.q.push_back(float(r.quality()));
  }
  if (stats) stats->quality_seconds += seconds_since(t0);
  return out;
}

void attach_impostor(vk::Context& ctx, TreeModel& model, uint32_t views, uint32_t size0, ImpostorBakeStats* stats) {
  model.impostor = bake_impostor_atlases(ctx, model, stats);
  ImpostorQuality quality = measure_impostor_quality(ctx, model, views, size0, stats);
  model.impostor.q = quality.q;
  model.impostor.cutoff = quality.cutoff;
}

}  // namespace forest
