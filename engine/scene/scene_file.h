// Scene files (TOML): resolution, camera, sun and sky, terrain, species and placement.
// Every key is checked; unknown keys, wrong types, out-of-range numbers and NaN are
// InputErrors naming file, line and key.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/prune_mode.h"

namespace forest {

struct CameraDesc {
  glm::vec3 position{0.0f, 20.0f, -80.0f};
  glm::vec3 target{0.0f, 5.0f, 0.0f};
  float fov_deg = 50.0f;  // vertical
  float near = 0.1f;
  float far = 2000.0f;    // culling distance
  // > 0: an orthographic camera this many metres tall (width from the aspect), depth linear
  // from `near` (1) to `far` (0); fov_deg is then unused. Set in code by measurements
  // (engine/tools/measure/), not read from scene files.
  float ortho_height = 0.0f;
  // Shift of the image in normalized device coordinates (x right, y down; 2 = the frame's
  // width or height): sub-pixel offsets for measurements, not read from scene files.
  glm::vec2 ndc_offset{0.0f};
};

// One keyframe of a camera path ([[path.key]]).
struct CameraKey {
  float time = 0.0f;  // seconds, strictly increasing along the path
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f};
  float fov_deg = 50.0f;
};

// A named camera path ([[path]]): `forest render --path NAME --time T | --frame N`.
struct CameraPath {
  std::string name;
  float fps = 30.0f;    // frames per second for --frame and benchmarks
  bool loop = false;    // time wraps; the last key should repeat the first
  std::vector<CameraKey> keys;
  int line = 0;
};

struct SkyDesc {
  glm::vec3 sun_direction{0.45f, 0.75f, 0.35f};  // toward the sun, normalized on load
  float sun_intensity = 3.0f;
  glm::vec3 zenith{0.18f, 0.35f, 0.75f};   // linear RGB
  glm::vec3 horizon{0.62f, 0.72f, 0.85f};
  float fog_density = 0.002f;              // per meter
};

struct TerrainDesc {
  float size = 400.0f;       // square side, meters, centered at the origin
  uint32_t resolution = 128; // grid cells per side
  float height = 20.0f;      // peak-to-valley amplitude, meters
  float feature_size = 120.0f;  // wavelength of the largest hills, meters
  uint32_t octaves = 5;
  uint64_t seed = 1;
  // Heightmap image instead of noise (8/16-bit PNG, EXR, ... via OIIO): the first channel,
  // normalized to [0, 1], maps linearly to [height_min, height_min + height] meters and
  // covers the whole `size` square (top row of the image = −z edge). Sampled bilinearly.
  std::filesystem::path heightmap;
  float height_min = 0.0f;
};

// How a species spec is baked when it is generated on first use ([bake]); part of the
// species cache key.
struct BakeDesc {
  std::string priority = "combined";
  uint32_t views = 6;
  uint32_t resolution = 512;  // projected size of the PR tables' size 0 (px across the bounding sphere)
  bool impostor = true;       // bake the impostor (impostor_bake.h); false: meshes only (quicker bakes)
};

struct SpeciesDesc {
  std::filesystem::path preset;  // species TOML (generated on load), or
  std::filesystem::path model;   // a .glb asset
  std::optional<uint64_t> seed;  // generation seed, overrides the preset's
  float weight = 1.0f;
  int line = 0;                  // for messages
};

struct PlacementDesc {
  uint32_t count = 0;
  uint64_t seed = 1;
  float min_spacing = 3.0f;  // meters between trunks
  float radius = 150.0f;     // trees fall within this distance of `center`
  glm::vec2 center{0.0f};    // x, z
  float scale_min = 0.8f, scale_max = 1.2f;
  float max_slope_deg = 35.0f;
  // Thomas cluster process on top of the spacing rule: `clusters` parent points uniform in
  // the disc, trees offset from a random parent by a Gaussian of σ = cluster_radius.
  // 0 clusters = uniform (Poisson-disc-like) placement.
  uint32_t clusters = 0;
  float cluster_radius = 10.0f;
};

struct TreeDesc {  // a hand-placed tree
  uint32_t species = 0;
  float x = 0.0f, z = 0.0f;
  float scale = 1.0f;
  float yaw_deg = 0.0f;
};

struct SceneDesc {
  std::filesystem::path file;
  uint32_t width = 1280, height = 720;
  uint32_t samples = 4;  // MSAA samples per pixel: 1, 2, 4 or 8
  float lod_error_pixels = 1.0f;  // branch LOD: allowed projected error; 0 = always LOD0
  PruneMode prune_mode = PruneMode::full;  // [render] mode
  float prune_distance = 400.0f;  // meters at which the normalized distance d reaches 1
  // The frame prune_distance is stated for, as its focal length in pixels (height / (2 tan(fov / 2))):
  // a scene file's own [render] height and [camera] fov. A frame of another height or fov scales
  // the distance by its own focal length over this one, so a tree prunes alike wherever it covers
  // as many pixels (Cook et al. 2007 prune by screen size). 0: the distance is used as given.
  float prune_focal_pixels = 0.0f;
  float quality = 0.95f;          // [render] quality: the PR quality Q mode "target" keeps per tree
  float transition = 0.1f;        // Cook's transition band t: fraction of the prefix that shrinks
  bool lambda_view = false;       // [render] view = "lambda": color trees by detail level
  bool mask_view = false;         // [render] view = "mask": coverage only (white trees on black), for forest compare
  bool occlusion = false;         // [render] occlusion: depth-buffer occlusion feedback (Neubert 2012 §7.4)
  bool shadows = true;            // [render] shadows: the sun's cascaded shadow maps (shadow_pass.h)
  bool impostors = false;         // [render] impostors: far trees as impostors where their baked Q allows (impostor_pass.h)
  float shadow_distance = 150.0f;  // [render] view depth (m) the cascades cover; beyond it, no sun shadows
  uint32_t shadow_resolution = 0;  // [render] texels per side of each cascade; 0: shadow_resolution_for(height)
  // [render] leaf_shadows = "leaf" (default): a leaf reads the shadow map once, at its centre;
  // "fragment": per fragment, sharper where a shadow edge crosses a near leaf, slower (lighting.glsl).
  bool leaf_shadows_per_fragment = false;
  float exposure = 1.0f;          // [render] scene-linear multiplier before the filmic tone map
  CameraDesc camera;
  SkyDesc sky;
  TerrainDesc terrain;
  std::vector<SpeciesDesc> species;
  PlacementDesc placement;
  std::vector<TreeDesc> trees;
  std::vector<CameraPath> paths;
  BakeDesc bake;
};

SceneDesc load_scene_file(const std::filesystem::path& file);
SceneDesc parse_scene_text(const std::string& text, const std::string& name,
                           const std::filesystem::path& base_dir);

}  // namespace forest
