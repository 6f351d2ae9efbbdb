// The scenes of the GPU tests: scene-file text written key by key (the tests' scenes share
// one layout and differ in a few values), scenes built in code around given models, and the
// broadleaf preset they mostly draw.
#pragma once
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "generators/core/text_file.h"
#include "generators/species/registry.h"
#include "tests/common/test_files.h"

namespace forest::test {

// The text of a small scene file: [render], [camera], [terrain], one [[species]] preset and
// whatever `extra` adds. The defaults are the common test scene (160x120, single-sampled,
// looking at the origin from 24 m over gently rolling ground, broadleaf seed 11). An unset
// optional key is not written at all: the parser's default applies.
struct SceneText {
  std::optional<uint32_t> width = 160, height = 120, samples = 1;
  std::string render;  // more [render] lines ("mode = \"opt\"\n")
  glm::vec3 position{0.0f, 6.0f, -24.0f}, target{0.0f, 5.0f, 0.0f};
  std::optional<float> fov = 50.0f;
  float terrain_size = 200.0f;
  uint32_t terrain_resolution = 32;
  float terrain_height = 1.0f;
  std::optional<uint64_t> terrain_seed = 3;
  std::string species = "broadleaf";  // scenes/species/<species>.toml; empty: no [[species]]
  std::optional<uint64_t> species_seed = 11;
  std::string extra;  // tables after the species ([bake], [[tree]], [placement])

  std::string str() const {
    std::ostringstream t;
    auto vec = [&](glm::vec3 v) { t << "[" << v.x << ", " << v.y << ", " << v.z << "]\n"; };
    t << "[render]\n";
    if (width) t << "width = " << *width << "\n";
    if (height) t << "height = " << *height << "\n";
    if (samples) t << "samples = " << *samples << "\n";
    t << render << "[camera]\nposition = ";
    vec(position);
    t << "target = ";
    vec(target);
    if (fov) t << "fov = " << *fov << "\n";
    t << "[terrain]\nsize = " << terrain_size << "\nresolution = " << terrain_resolution << "\nheight = " << terrain_height
      << "\n";
    if (terrain_seed) t << "seed = " << *terrain_seed << "\n";
    if (!species.empty()) {
      t << "[[species]]\npreset = \"species/" << species << ".toml\"\n";
      if (species_seed) t << "seed = " << *species_seed << "\n";
    }
    return t.str() + extra;
  }
};

// A scene file's text parsed as `name` in scenes/ (where its presets are found).
inline SceneDesc parse_scene(const std::string& text, const std::string& name = "test.toml") {
  return parse_scene_text(text, name, kSourceDir + "/scenes");
}

// Flat ground without fog, single-sampled: the start of a scene built in code.
inline SceneDesc flat_ground(uint32_t width, uint32_t height, float terrain_size) {
  SceneDesc d;
  d.width = width;
  d.height = height;
  d.samples = 1;
  d.sky.fog_density = 0.0f;
  d.terrain.size = terrain_size;
  d.terrain.resolution = 8;
  d.terrain.height = 0.0f;
  return d;
}

// The scene of `desc` drawing `models` (no species files): its terrain and its trees, the
// hand-placed ones and those of [placement].
inline Scene scene_of(SceneDesc desc, std::vector<TreeModel> models) {
  Scene s;
  s.desc = std::move(desc);
  s.terrain = make_terrain(s.desc.terrain);
  s.models = std::move(models);
  s.instances = place_trees(s.desc, s.terrain);
  return s;
}

// The broadleaf preset at seed 11, as the test scenes' [[species]] make it (not baked).
inline TreeModel broadleaf() {
  return generate_from_species(kSourceDir + "/scenes/species/broadleaf.toml", GenerateOptions{11});
}

// The broadleaf skeleton with coarse foliage: single 0.32 m leaves (several pixels wide at
// every test resolution), for checks of the measurement itself rather than of the foliage.
inline TreeModel coarse_broadleaf() {
  std::string text = read_text_file(kSourceDir + "/scenes/species/broadleaf.toml");
  auto set = [&](const std::string& key, const std::string& value) {
    size_t at = text.find("\n" + key + " = ") + 1;
    text.replace(at, text.find('\n', at) - at, key + " = " + value);
  };
  set("foliage", "\"leaves\"");
  set("leaf_size", "0.32");
  set("shoot_spacing", "0.6");
  return generate_from_species_text(text, kSourceDir + "/scenes/species/broadleaf.toml", GenerateOptions{11});
}

}  // namespace forest::test
