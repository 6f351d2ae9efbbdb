#include "engine/scene/scene_file.h"

#include <cmath>
#include <limits>

#include "engine/scene/camera.h"
#include "generators/core/limits.h"
#include "generators/core/toml_reader.h"
#include "gpu_types.h"

namespace forest {

namespace {

constexpr double kBig = 1e6;  // meters: anything beyond is certainly a typo

// A two-element array of finite numbers in [lo, hi], such as [x, z] or [min, max].
glm::vec2 read_pair(const TomlTable& t, const char* key, double lo, double hi) {
  auto a = t.raw().get(key)->as_array();
  if (!a || a->size() != 2) t.fail(key, "expected an array of 2 numbers");
  glm::vec2 v;
  for (int i = 0; i < 2; ++i) {
    auto n = a->get(size_t(i));
    double x = n->is_integer() ? double(n->as_integer()->get())
               : n->is_floating_point() ? n->as_floating_point()->get() : NAN;
    if (!std::isfinite(x) || x < lo || x > hi)
      t.fail(key, "expected 2 finite numbers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    v[i] = float(x);
  }
  return v;
}

void read_render(const TomlTable& t, SceneDesc& s) {
  t.check_keys({"width", "height", "samples", "lod_error_pixels", "mode", "prune_distance", "transition", "view",
                "occlusion", "shadows", "shadow_distance", "shadow_resolution", "exposure", "quality", "impostors", "leaf_shadows"});
  s.width = uint32_t(t.integer("width", s.width, kMinFrameSide, kMaxFrameSide));
  s.height = uint32_t(t.integer("height", s.height, kMinFrameSide, kMaxFrameSide));
  s.samples = uint32_t(t.integer("samples", s.samples, 1, 8));
  if (s.samples & (s.samples - 1)) t.fail("samples", "must be 1, 2, 4 or 8, got " + std::to_string(s.samples));
  s.lod_error_pixels = float(t.number("lod_error_pixels", s.lod_error_pixels, 0.0, 1000.0));
  s.prune_mode = *parse_prune_mode(t.choice("mode", "full", prune_mode_names()));
  s.prune_distance = float(t.number("prune_distance", s.prune_distance, 1e-2, kBig));
  s.transition = float(t.number("transition", s.transition, 0.0, 1.0));
  s.quality = float(t.number("quality", s.quality, 0.0, 1.0));
  std::string view = t.choice("view", "shaded", {"shaded", "lambda", "mask"});
  s.lambda_view = view == "lambda";
  s.mask_view = view == "mask";
  s.occlusion = t.boolean("occlusion", s.occlusion);
  s.shadows = t.boolean("shadows", s.shadows);
  s.impostors = t.boolean("impostors", s.impostors);
  s.shadow_distance = float(t.number("shadow_distance", s.shadow_distance, 1.0, 1e5));
  s.shadow_resolution = uint32_t(t.integer("shadow_resolution", s.shadow_resolution, 64, kMaxShadowResolution));
  s.exposure = float(t.number("exposure", s.exposure, 1e-3, 1e3));
  s.leaf_shadows_per_fragment = t.choice("leaf_shadows", "leaf", {"leaf", "fragment"}) == "fragment";
}

void read_camera(const TomlTable& t, CameraDesc& c) {
  t.check_keys({"position", "target", "fov", "near", "far"});
  c.position = t.vec3("position", c.position, -kBig, kBig);
  c.target = t.vec3("target", c.target, -kBig, kBig);
  c.fov_deg = float(t.number("fov", c.fov_deg, 1.0, 170.0));
  c.near = float(t.number("near", c.near, 1e-3, 100.0));
  c.far = float(t.number("far", c.far, 1.0, kBig));
  if (glm::length(c.target - c.position) < 1e-4f) t.fail("target", "must differ from camera.position");
  if (c.far <= c.near) t.fail("far", "must be greater than camera.near");
}

void read_sky(const TomlTable& t, SkyDesc& s) {
  t.check_keys({"sun_direction", "sun_intensity", "zenith", "horizon", "fog_density"});
  s.sun_direction = t.vec3("sun_direction", s.sun_direction, -1e3, 1e3);
  if (glm::length(s.sun_direction) < 1e-6f) t.fail("sun_direction", "must not be the zero vector");
  s.sun_direction = glm::normalize(s.sun_direction);
  s.sun_intensity = float(t.number("sun_intensity", s.sun_intensity, 0.0, 100.0));
  s.zenith = t.vec3("zenith", s.zenith, 0.0, 100.0);
  s.horizon = t.vec3("horizon", s.horizon, 0.0, 100.0);
  s.fog_density = float(t.number("fog_density", s.fog_density, 0.0, 1.0));
}

void read_terrain(const TomlTable& t, TerrainDesc& d, const std::filesystem::path& base) {
  t.check_keys({"size", "resolution", "height", "feature_size", "octaves", "seed", "heightmap", "height_min"});
  d.size = float(t.number("size", d.size, 1.0, 1e5));
  d.resolution = uint32_t(t.integer("resolution", d.resolution, 1, 2048));
  d.height = float(t.number("height", d.height, 0.0, 1e4));
  d.feature_size = float(t.number("feature_size", d.feature_size, 1.0, 1e5));
  d.octaves = uint32_t(t.integer("octaves", d.octaves, 1, 12));
  d.seed = uint64_t(t.integer("seed", int64_t(d.seed), 0, std::numeric_limits<int64_t>::max()));
  d.height_min = float(t.number("height_min", d.height_min, -1e4, 1e4));
  if (t.has("heightmap")) {
    std::filesystem::path p = t.string("heightmap");
    if (p.empty()) t.fail("heightmap", "must not be empty");
    if (p.is_relative()) p = base / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) t.fail("heightmap", "file not found: " + p.string());
    d.heightmap = p;
  }
}

void read_bake(const TomlTable& t, BakeDesc& b) {
  t.check_keys({"priority", "views", "resolution", "impostor"});
  b.priority = t.choice("priority", b.priority, {"random", "density", "orientation", "combined", "layered"});
  b.views = uint32_t(t.integer("views", b.views, 1, 64));
  b.resolution = uint32_t(t.integer("resolution", b.resolution, kMinBakeResolution, kMaxPrSize0));
  b.impostor = t.boolean("impostor", b.impostor);
}

CameraPath read_path(const TomlTable& t) {
  t.check_keys({"name", "fps", "loop", "key"});
  CameraPath p;
  p.line = int(t.raw().source().begin.line);
  p.name = t.string("name");
  if (p.name.empty()) t.fail("name", "must not be empty");
  p.fps = float(t.number("fps", p.fps, 1e-3, 1e4));
  p.loop = t.boolean("loop", false);
  std::vector<TomlTable> keys = t.tables("key");
  if (keys.size() < 2) t.fail("key", "a path needs at least 2 keys ([[path.key]] with time, position, target)");
  for (const TomlTable& k : keys) {
    k.check_keys({"time", "position", "target", "fov"});
    CameraKey key;
    key.time = float(k.number("time", 0.0, kBig));
    key.position = k.vec3("position", -kBig, kBig);
    key.target = k.vec3("target", -kBig, kBig);
    key.fov_deg = float(k.number("fov", 50.0, 1.0, 170.0));
    if (glm::length(key.target - key.position) < 1e-4f) k.fail("target", "must differ from position");
    if (!p.keys.empty() && key.time <= p.keys.back().time)
      k.fail("time", "must be greater than the previous key's time (" + std::to_string(p.keys.back().time) + ")");
    p.keys.push_back(key);
  }
  return p;
}

SpeciesDesc read_species(const TomlTable& t, const std::filesystem::path& base) {
  t.check_keys({"preset", "model", "seed", "weight"});
  SpeciesDesc s;
  s.line = int(t.raw().source().begin.line);
  if (t.has("preset") == t.has("model"))
    t.fail(t.has("preset") ? "model" : "preset", "give exactly one of 'preset' (species TOML) or 'model' (.glb)");
  auto resolve = [&](const std::string& key) {
    std::filesystem::path p = t.string(key);
    if (p.empty()) t.fail(key, "must not be empty");
    if (p.is_relative()) p = base / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) t.fail(key, "file not found: " + p.string());
    return p;
  };
  if (t.has("preset")) s.preset = resolve("preset");
  if (t.has("model")) s.model = resolve("model");
  if (t.has("seed")) s.seed = uint64_t(t.integer("seed", 0, std::numeric_limits<int64_t>::max()));
  s.weight = float(t.number("weight", 1.0, 0.0, 1e6));
  return s;
}

void read_placement(const TomlTable& t, PlacementDesc& p) {
  t.check_keys({"count", "seed", "min_spacing", "radius", "center", "scale", "max_slope", "clusters", "cluster_radius"});
  p.count = uint32_t(t.integer("count", 0, 0, kMaxTreeInstances));
  p.seed = uint64_t(t.integer("seed", int64_t(p.seed), 0, std::numeric_limits<int64_t>::max()));
  p.min_spacing = float(t.number("min_spacing", p.min_spacing, 0.0, 1e4));
  p.radius = float(t.number("radius", p.radius, 0.0, kBig));
  if (t.has("center")) p.center = read_pair(t, "center", -kBig, kBig);
  if (t.has("scale")) {
    glm::vec2 v = read_pair(t, "scale", 1e-3, 100.0);
    if (v.x > v.y) t.fail("scale", "min must not exceed max");
    p.scale_min = v.x;
    p.scale_max = v.y;
  }
  p.max_slope_deg = float(t.number("max_slope", p.max_slope_deg, 0.0, 90.0));
  p.clusters = uint32_t(t.integer("clusters", p.clusters, 0, 1'000'000));
  p.cluster_radius = float(t.number("cluster_radius", p.cluster_radius, 1e-2, kBig));
}

TreeDesc read_tree(const TomlTable& t, size_t species_count) {
  t.check_keys({"species", "x", "z", "scale", "yaw"});
  TreeDesc d;
  d.species = uint32_t(t.integer("species", 0, 0, 1'000'000));
  if (d.species >= species_count)
    t.fail("species", "index " + std::to_string(d.species) + " but only " +
                          std::to_string(species_count) + " [[species]] defined");
  d.x = float(t.number("x", -kBig, kBig));
  d.z = float(t.number("z", -kBig, kBig));
  d.scale = float(t.number("scale", 1.0, 1e-3, 100.0));
  d.yaw_deg = float(t.number("yaw", 0.0, -1e4, 1e4));
  return d;
}

SceneDesc read_scene(const TomlTable& root, const std::filesystem::path& base) {
  SceneDesc s;
  root.check_keys({"render", "camera", "sky", "terrain", "species", "placement", "tree", "path", "bake"});
  if (auto t = root.table("render")) read_render(*t, s);
  if (auto t = root.table("camera")) read_camera(*t, s.camera);
  s.prune_focal_pixels = focal_pixels(float(s.height), s.camera.fov_deg);
  if (auto t = root.table("sky")) read_sky(*t, s.sky);
  if (auto t = root.table("terrain")) read_terrain(*t, s.terrain, base);
  if (auto t = root.table("bake")) read_bake(*t, s.bake);
  for (const TomlTable& t : root.tables("path")) {
    CameraPath p = read_path(t);
    for (const CameraPath& q : s.paths)
      if (q.name == p.name) t.fail("name", "a path named '" + p.name + "' is already defined");
    s.paths.push_back(std::move(p));
  }
  for (const TomlTable& t : root.tables("species")) s.species.push_back(read_species(t, base));
  if (auto t = root.table("placement")) {
    read_placement(*t, s.placement);
  }
  if (s.species.size() > kMaxSceneSpecies)
    root.fail("species", std::to_string(s.species.size()) + " [[species]], more than the limit of " +
                             std::to_string(kMaxSceneSpecies));
  for (const TomlTable& t : root.tables("tree")) s.trees.push_back(read_tree(t, s.species.size()));
  if (uint64_t(s.placement.count) + s.trees.size() > kMaxTreeInstances)
    root.fail(s.trees.empty() ? "placement" : "tree",
              std::to_string(uint64_t(s.placement.count) + s.trees.size()) +
                  " trees (placement.count + [[tree]]), more than the limit of " + std::to_string(kMaxTreeInstances));
  if ((s.placement.count > 0 || !s.trees.empty()) && s.species.empty())
    root.fail("species", "trees are placed but no [[species]] is defined");
  if (s.placement.count > 0) {
    double total = 0.0;
    for (const SpeciesDesc& sp : s.species) total += sp.weight;
    if (total <= 0.0) root.fail("species", "the species weights sum to 0");
  }
  return s;
}

}  // namespace

SceneDesc parse_scene_text(const std::string& text, const std::string& name,
                           const std::filesystem::path& base_dir) {
  TomlDocument doc = TomlDocument::parse(text, name);
  SceneDesc s = read_scene(doc.root(), base_dir);
  s.file = name;
  return s;
}

SceneDesc load_scene_file(const std::filesystem::path& file) {
  TomlDocument doc = TomlDocument::load(file);
  SceneDesc s = read_scene(doc.root(), file.parent_path());
  s.file = file;
  return s;
}

}  // namespace forest
