// Should the device that measured a species cache entry be part of the entry's key? Two
// conformant Vulkan devices rasterize the same triangles differently only at sample points on
// or within sub-pixel precision of an edge (coverage rules, subPixelPrecisionBits ≥ 4; the
// standard sample locations are fixed). Moving the model by a fraction of a pixel changes the
// coverage decision of every edge sample at once, a larger change than any two devices make,
// so how far the PR tables move under such a shift bounds how far they can move between
// devices. Usage:
//   table_shift_bench [--species PRESET] [--views N] [--resolution PX] [--shifts 0.0625,0.25,0.5]
// Bakes the preset's tables (priority combined, no impostor) as generated and moved by each
// shift (pixels of the tables' size 0, along the first view's image x and y), and prints the
// largest and mean change of q_opt, q_inverse and λ_opt over every λ, d and size, against
// the equal-quality tolerance kEqualQualityTolerance. Single run, one device.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/tools/bake/tree_bake.h"
#include "engine/vk/context.h"
#include "generators/species/registry.h"
#include "prune_math.h"

using namespace forest;

namespace {

struct Options {
  std::string species = FOREST_SOURCE_DIR "/scenes/species/broadleaf.toml";
  uint32_t views = 6, resolution = 512;
  std::vector<double> shifts{0.0625, 0.25, 0.5};
};

void move(Mesh& m, glm::vec3 by) {
  for (Vertex& v : m.vertices) v.position += by;
}

// The model moved by `by` with its bounding sphere left where it was: every view's camera
// (aimed at the sphere) then sees the tree moved across the image.
TreeModel moved(const TreeModel& base, glm::vec3 by) {
  TreeModel m = base;
  move(m.branches, by);
  for (MeshLod& l : m.branch_lods) move(l.mesh, by);
  for (LeafPlacement& l : m.leaves) l.position += by;
  return m;
}

struct Change {
  double max = 0, sum = 0;
  size_t n = 0;
  void add(double a, double b) {
    max = std::max(max, std::abs(a - b));
    sum += std::abs(a - b);
    ++n;
  }
  double mean() const { return n ? sum / double(n) : 0.0; }
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 >= argc) {
      std::fprintf(stderr, "table_shift_bench: %s needs a value\n", a.c_str());
      return 2;
    }
    std::string v = argv[++i];
    if (a == "--species") o.species = v;
    else if (a == "--views") o.views = uint32_t(std::stoul(v));
    else if (a == "--resolution") o.resolution = uint32_t(std::stoul(v));
    else if (a == "--shifts") {
      o.shifts.clear();
      for (size_t at = 0; at <= v.size();) {
        size_t end = std::min(v.find(',', at), v.size());
        o.shifts.push_back(std::stod(v.substr(at, end - at)));
        at = end + 1;
      }
    } else {
      std::fprintf(stderr, "table_shift_bench: unknown argument %s\n", a.c_str());
      return 2;
    }
  }
  vk::Context ctx;
  try {
    vk::create_context(ctx, {});
    std::printf("device: %s\n", ctx.properties.deviceName);
    const TreeModel base = generate_from_species(o.species);
    TreeBakeSettings settings;
    settings.views = o.views;
    settings.resolution = o.resolution;
    settings.impostor = false;
    TreeModel reference = base;
    bake_tree_model(ctx, reference, settings);
    const PrTables& ref = *reference.bake.pr_tables;
    // One pixel of size 0 (size0 px across the bounding sphere's diameter), in metres. The
    // first view looks along +z from −z, so its image axes are x and y.
    const float pixel = 2.0f * base.bounding_sphere.w / float(o.resolution);
    std::printf("%s: %zu leaves, %u views, size 0 = %u px (1 px = %.4f m); tolerance %.3f\n", o.species.c_str(),
                base.leaves.size(), o.views, o.resolution, double(pixel), double(kEqualQualityTolerance));
    std::printf("shift_px  max|dq_opt|  mean|dq_opt|  max|dq_inverse|  max|dlambda_opt|  mean|dlambda_opt|\n");
    for (double shift : o.shifts) {
      TreeModel m = moved(base, glm::vec3(1.0f, 1.0f, 0.0f) * float(shift) * pixel / std::sqrt(2.0f));
      bake_tree_model(ctx, m, settings);
      const PrTables& t = *m.bake.pr_tables;
      Change q, qi, lambda;
      std::string per_size;  // mean |Δq_opt| at each size
      for (size_t b = 0; b < ref.sizes.size(); ++b) {
        Change qb;
        for (size_t i = 0; i < ref.sizes[b].q_opt.size(); ++i) {
          q.add(ref.sizes[b].q_opt[i], t.sizes[b].q_opt[i]);
          qb.add(ref.sizes[b].q_opt[i], t.sizes[b].q_opt[i]);
          qi.add(ref.sizes[b].q_inverse[i], t.sizes[b].q_inverse[i]);
        }
        for (size_t j = 0; j < ref.sizes[b].lambda_opt.size(); ++j)
          lambda.add(ref.sizes[b].lambda_opt[j], t.sizes[b].lambda_opt[j]);
        char cell[64];
        std::snprintf(cell, sizeof cell, " %.0fpx %.4f/%.4f", double(pr_size(ref.size0, uint32_t(b))), qb.mean(), qb.max);
        per_size += cell;
      }
      std::printf("%8.4f  %11.5f  %12.5f  %15.5f  %16.5f  %17.5f\n", shift, q.max, q.mean(), qi.max, lambda.max,
                  lambda.mean());
      std::printf("          mean/max |dq_opt| per size:%s\n", per_size.c_str());
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "table_shift_bench: %s\n", e.what());
    vk::destroy_context(ctx);
    return 1;
  }
  vk::destroy_context(ctx);
  return 0;
}
