// The shared look keys: species keys that every method accepts and that only the model stage
// reads (leaf card and texture, bark texture pattern, bark and leaf material colours, tube
// ring sides). They draw no
// random numbers and never touch the skeleton, so changing one changes how a tree looks, not
// its branches. One reader, one set of defaults, for all methods.
#pragma once
#include <string_view>

#include <glm/glm.hpp>

#include "generators/mesh/bark_texture.h"
#include "generators/mesh/leaf_texture.h"

namespace forest {

class TomlTable;

struct LookKeys {
  LeafShape leaf_shape = LeafShape::ovate;    // leaf_shape: leaf texture and card outline
  BarkPattern bark_pattern = BarkPattern::generic;  // bark_pattern: bark texture and its tile size
  glm::vec3 bark_color{0.30f, 0.22f, 0.15f};  // bark_color: bark material, linear RGB
  glm::vec3 leaf_color{0.18f, 0.35f, 0.08f};  // leaf_color: leaf material, linear RGB
  int ring_sides_min = 3;                     // ring_sides_min: tube sides of the thinnest chains
  int ring_sides_max = 8;                     // ring_sides_max: tube sides of the trunk
};

// The keys read_look_keys reads; the registry accepts them for every method.
inline constexpr std::string_view kLookKeys[] = {"leaf_shape",     "bark_pattern",  "bark_color",
                                                 "leaf_color",     "ring_sides_min", "ring_sides_max"};

// Reads the look keys of a species table; absent keys keep LookKeys' defaults. Out of range,
// wrong type or ring_sides_max < ring_sides_min -> InputError naming file, line and key.
LookKeys read_look_keys(const TomlTable& species);

}  // namespace forest
