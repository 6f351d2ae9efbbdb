// How much of PR's quality is registration? Q (Neubert 2012 §7.2.2, (7.7)) compares two
// coverage images pixel by pixel, so at small projected sizes, where leaves are at or below a
// pixel, it rewards a representation that puts its edges on the very pixels the full-detail
// model does. A pruned mesh keeps its surviving leaves exactly where full detail has them; an
// impostor (impostor_bake.h), or the full-detail tree moved by a fraction of a pixel, does not.
// This bench measures, per model and PR table size p:
//   - Q of the full-detail model against itself with the camera moved sideways by ¼ and ½
//     pixel: what a shift no viewer can see costs in Q (the registration floor);
//   - Q of the baked impostor at its coverage cutoff (measure_impostor_quality);
//   - the λ at which the pruned mesh's q_opt(λ, p) reaches each of them: below λ_imp the
//     impostor switch (impostor_switch.glsl) takes the tree; between λ_imp and λ_half the mesh
//     is kept although its Q exceeds the impostor's by less than a half-pixel shift costs.
// Usage:
//   registration_bench [--species PRESET]... [--views N] [--out FILE.md]
// Models come from the species cache (default bake settings; baked on a miss). One run, one
// device; the figures are Q, not times.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/render/renderer.h"
#include "engine/tools/gallery/contact_sheet.h"
#include "engine/tools/bake/impostor_bake.h"
#include "engine/tools/bake/pr_bake.h"
#include "engine/tools/bake/species_cache.h"
#include "engine/vk/context.h"
#include "prune_math.h"

using namespace forest;

namespace {

struct Options {
  std::vector<std::string> species;
  uint32_t views = 6;
  std::string out;
};

// `cam` moved along its image x by `pixels` of its `resolution`-pixel image, measured at the
// distance of its target (the bounding sphere's centre).
CameraDesc moved_sideways(CameraDesc cam, float pixels, uint32_t resolution) {
  const glm::vec3 forward = glm::normalize(cam.target - cam.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const float distance = glm::length(cam.target - cam.position);
  const float pixel = 2.0f * distance * std::tan(glm::radians(cam.fov_deg) * 0.5f) / float(resolution);
  cam.position += right * pixel * pixels;
  cam.target += right * pixel * pixels;
  return cam;
}

// Q of full detail against itself moved by each of `shifts` pixels, at every PR size.
std::vector<std::vector<double>> shifted_quality(vk::Context& ctx, const TreeModel& model, uint32_t views,
                                                 uint32_t size0, const std::vector<float>& shifts) {
  const uint32_t resolution = pr_render_resolution(size0);
  Scene scene = make_model_scene(model, resolution, 1);
  Renderer renderer(ctx, scene, resolution, resolution, 1);
  std::vector<std::vector<double>> q(shifts.size(), std::vector<double>(PR_SIZES));
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const uint32_t size = std::max(uint32_t(std::lround(pr_size(float(size0), b))), 1u);
    std::vector<PrResult> pr(shifts.size());
    for (const CameraDesc& cam : pr_views(model.bounding_sphere, views, size, resolution)) {
      renderer.render_reference(cam, FrameSettings{});
      for (size_t k = 0; k < shifts.size(); ++k)
        pr[k] += renderer.compare_with_reference(moved_sideways(cam, shifts[k], resolution), FrameSettings{});
    }
    for (size_t k = 0; k < shifts.size(); ++k) q[k][b] = pr[k].quality();
  }
  return q;
}

// The smallest λ (linear between the table's samples) whose q_opt reaches `quality`; 1 if none.
double lambda_reaching(const std::vector<float>& q_opt, double quality) {
  for (size_t i = 1; i < q_opt.size(); ++i)
    if (q_opt[i] >= quality) {
      const double q0 = q_opt[i - 1], q1 = q_opt[i];
      const double t = q1 > q0 ? std::clamp((quality - q0) / (q1 - q0), 0.0, 1.0) : 1.0;
      return (double(i - 1) + t) / double(q_opt.size() - 1);
    }
  return 1.0;
}

std::string report(vk::Context& ctx, const std::string& preset, uint32_t views) {
  SpeciesDesc species;
  species.preset = preset;
  CachedSpecies cached = load_or_bake_species(species, BakeDesc{}, default_cache_dir(), &ctx);
  const TreeModel& model = cached.model;
  if (!model.bake.pr_tables || model.impostor.q.empty())
    throw std::runtime_error(preset + ": no PR tables or no impostor in the baked model");
  const PrTables& tables = *model.bake.pr_tables;
  const uint32_t size0 = uint32_t(std::lround(tables.size0));
  const std::vector<float> shifts{0.25f, 0.5f};
  const auto shifted = shifted_quality(ctx, model, views, size0, shifts);
  const ImpostorQuality impostor = measure_impostor_quality(ctx, model, views, size0);
  std::string name = std::filesystem::path(preset).stem().string();
  std::string md;
  char row[256];
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const std::vector<float>& q_opt = tables.sizes[b].q_opt;
    std::snprintf(row, sizeof row, "| %s | %.0f | %.3f | %.3f | %.3f | %.2f | %.2f |\n", b ? "" : name.c_str(),
                  double(pr_size(tables.size0, b)), shifted[0][b], shifted[1][b], double(impostor.q[b]),
                  lambda_reaching(q_opt, impostor.q[b]), lambda_reaching(q_opt, shifted[1][b]));
    md += row;
  }
  std::printf("%s", md.c_str());
  std::fflush(stdout);
  return md;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "registration_bench: %s needs a value\n", a.c_str());
      return 2;
    }
    std::string v = argv[++i];
    if (a == "--species") o.species.push_back(v);
    else if (a == "--views") o.views = uint32_t(std::stoul(v));
    else if (a == "--out") o.out = v;
    else {
      std::fprintf(stderr, "registration_bench: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  if (o.species.empty()) o.species = {FOREST_SOURCE_DIR "/scenes/species/broadleaf.toml"};
  vk::Context ctx;
  int rc = 0;
  try {
    vk::create_context(ctx, {});
    std::string md = std::string("Device: ") + ctx.properties.deviceName + ", " + std::to_string(o.views) +
                     " PR views per size.\n\n"
                     "| model | size px | Q full detail moved 1/4 px | moved 1/2 px | impostor | "
                     "lambda where q_opt reaches the impostor | lambda where q_opt reaches 1/2 px |\n"
                     "|---|---|---|---|---|---|---|\n";
    std::printf("%s", md.c_str());
    for (const std::string& s : o.species) md += report(ctx, s, o.views);
    if (!o.out.empty()) std::ofstream(o.out) << md;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "registration_bench: %s\n", e.what());
    rc = 1;
  }
  vk::destroy_context(ctx);
  return rc;
}
