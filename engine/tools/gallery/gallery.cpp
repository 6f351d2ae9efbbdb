#include "engine/tools/gallery/gallery.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/constants.hpp>

#include "engine/tools/gallery/human_figure.h"
#include "generators/core/input_error.h"
#include "generators/species/registry.h"

namespace forest {

std::vector<std::filesystem::path> list_species_presets(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir.string(), 0, "--species-dir", "folder does not exist");
  std::vector<std::filesystem::path> presets;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.path().extension() == ".toml" && e.is_regular_file()) presets.push_back(e.path());
  if (ec) throw InputError(dir.string(), 0, "--species-dir", "cannot list folder: " + ec.message());
  if (presets.empty()) throw InputError(dir.string(), 0, "--species-dir", "holds no species preset (*.toml)");
  std::sort(presets.begin(), presets.end());
  return presets;
}

uint32_t gallery_label_band(uint32_t size) { return std::max(20u, size / 6); }

namespace {

// The sphere every cell frames at common scale: from the ground to above the tallest tree.
glm::vec4 common_frame(const std::vector<TreeModel>& models) {
  float top = 2.0f;  // at least the human figure
  for (const TreeModel& m : models) top = std::max(top, m.bounding_sphere.y + m.bounding_sphere.w);
  return glm::vec4(0.0f, 0.5f * top, 0.0f, 0.52f * top);
}

// The human figure stands to the camera's right of the trunk, at 0.7 of the frame radius.
void add_human(Scene& scene, const CameraDesc& cam, float frame_radius) {
  glm::vec3 forward = cam.target - cam.position;
  glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  TreeDesc person;
  person.species = uint32_t(scene.models.size());
  person.x = right.x * 0.7f * frame_radius;
  person.z = right.z * 0.7f * frame_radius;
  // Facing the camera: the figure faces +Z, turn it toward -forward.
  person.yaw_deg = glm::degrees(std::atan2(-forward.x, -forward.z));
  scene.models.push_back(human_figure(1.8f));
  scene.desc.trees.push_back(person);
  scene.desc.terrain.size = std::max(scene.desc.terrain.size, 24.0f * frame_radius);  // no edge in view
  scene.terrain = make_terrain(scene.desc.terrain);
  scene.instances = place_trees(scene.desc, scene.terrain);
}

}  // namespace

FrameImage render_gallery(vk::Context& ctx, const std::vector<std::filesystem::path>& presets,
                          const GalleryOptions& options, std::vector<GalleryEntry>* entries,
                          const std::function<void(size_t, size_t)>& progress) {
  const size_t total = 2 * presets.size();
  size_t done = 0;
  auto step = [&] {
    ++done;
    if (progress) progress(done, total);
  };
  // All presets first: a bad file stops the gallery before any GPU work.
  std::vector<TreeModel> models;
  models.reserve(presets.size());
  for (const auto& p : presets) {
    models.push_back(generate_from_species(p));
    step();
  }
  const uint32_t band = gallery_label_band(options.size);
  const glm::vec4 frame = common_frame(models);
  std::vector<FrameImage> cells;
  for (size_t i = 0; i < models.size(); ++i) {
    const TreeModel& m = models[i];
    GalleryEntry e;
    e.name = presets[i].stem().string();
    e.method = m.meta.value("method", "");
    e.triangles = m.branches.indices.size() / 3;
    e.leaves = m.leaves.size();
    e.height = m.meta.value("height", 0.0);
    Scene scene = make_model_scene(m, options.size, options.samples);
    CameraDesc cam = orbit_camera(options.common_scale ? frame : m.bounding_sphere, glm::radians(options.azimuth_deg),
                                  glm::radians(options.elevation_deg), 30.0f);
    if (options.common_scale) add_human(scene, cam, frame.w);
    Renderer renderer(ctx, scene, options.size, options.size, options.samples);
    FrameImage image;
    renderer.render(cam, &image);
    char detail[160];
    std::snprintf(detail, sizeof detail, "%s  %zu tris  %zu leaves", e.method.c_str(), e.triangles, e.leaves);
    cells.push_back(add_label(image, {e.name, detail}, band));
    if (entries) entries->push_back(std::move(e));
    models[i] = TreeModel{};  // free the meshes as we go
    step();
  }
  uint32_t columns = options.columns > 0 ? options.columns
                                         : uint32_t(std::ceil(std::sqrt(double(cells.size()))));
  return compose_grid(cells, columns);
}

}  // namespace forest
