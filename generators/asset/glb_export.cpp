#include "generators/asset/glb_export.h"

#include <algorithm>

#include "generators/asset/asset_io.h"

namespace forest {

namespace fs = std::filesystem;

namespace {

fs::path lod_file(const fs::path& out, uint32_t level) {
  if (level == 0) return out;
  fs::path p = out;
  p.replace_filename(out.stem().string() + "_LOD" + std::to_string(level) + out.extension().string());
  return p;
}

// The coverage (sphere diameter ÷ screen height) below which an error of `error` metres
// projects to at most `pixels`: error · coverage · H ÷ (2 r) ≤ pixels.
float coverage_for(float error, float radius, const ExportOptions& o) {
  if (error <= 0.0f || radius <= 0.0f) return 1.0f;
  return std::min(1.0f, o.error_pixels * 2.0f * radius / (error * o.screen_height));
}

}  // namespace

std::vector<ExportedLod> export_model(const TreeModel& model, const fs::path& out, const ExportOptions& options) {
  const std::string name = out.stem().string();
  // The client's tree: bark, leaves and their textures only.
  TreeModel client;
  client.leaf_card = model.leaf_card;
  client.leaf_texture = model.leaf_texture;
  client.bark_texture = model.bark_texture;
  client.bark_normal = model.bark_normal;
  client.bark_tile_meters = model.bark_tile_meters;
  client.leaves = model.leaves;
  client.bounding_sphere = model.bounding_sphere;
  client.bark_color = model.bark_color;
  client.leaf_color = model.leaf_color;
  std::vector<ExportedLod> lods;
  const uint32_t levels = uint32_t(model.branch_lods.size()) + 1;
  try {
    for (uint32_t i = 0; i < levels; ++i) {
      ExportedLod e;
      e.file = lod_file(out, i);
      e.node = name + "_LOD" + std::to_string(i);
      e.level = i;
      e.error = i == 0 ? 0.0f : model.branch_lods[i - 1].error;
      e.screen_coverage = i == 0 ? 1.0f : coverage_for(e.error, model.bounding_sphere.w, options);
      client.branches = i == 0 ? model.branches : model.branch_lods[i - 1].mesh;
      e.branch_triangles = client.branches.indices.size() / 3;
      e.leaves = client.leaves.size();
      e.leaf_triangles = e.leaves * (client.leaf_card.indices.size() / 3);
      GlbOptions g;
      g.root_name = e.node;
      g.scene_name = name;
      g.flatten_leaves = options.flatten;
      g.forest_extras = false;
      g.root_extras = {{"lod", {{"level", i},
                                {"levels", levels},
                                {"error_meters", e.error},
                                {"screen_coverage", e.screen_coverage},
                                {"screen_coverage_at", {{"error_pixels", options.error_pixels},
                                                        {"screen_height", options.screen_height}}},
                                {"files", nlohmann::json::array()}}}};
      for (uint32_t k = 0; k < levels; ++k) g.root_extras["lod"]["files"].push_back(lod_file(out, k).filename().string());
      std::vector<uint8_t> bytes = encode_glb(client, g);
      write_file_atomic(e.file, bytes);
      lods.push_back(std::move(e));
      if (options.progress) options.progress(double(i + 1) / levels);
    }
  } catch (...) {
    // No partial output: the levels written before the failure go too.
    std::error_code ec;
    for (const ExportedLod& e : lods) fs::remove(e.file, ec);
    throw;
  }
  return lods;
}

}  // namespace forest
