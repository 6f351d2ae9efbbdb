#include "generators/model/look_keys.h"

#include "generators/core/toml_reader.h"

#include <string>
#include <vector>

namespace forest {

LookKeys read_look_keys(const TomlTable& t) {
  const LookKeys d;
  LookKeys k;
  std::vector<std::string> shapes;
  for (LeafShape s : kLeafShapes) shapes.push_back(leaf_shape_name(s));
  k.leaf_shape = *parse_leaf_shape(t.choice("leaf_shape", leaf_shape_name(d.leaf_shape), shapes));
  k.bark_pattern = *parse_bark_pattern(t.choice("bark_pattern", bark_pattern_name(d.bark_pattern),
                                                {"furrowed", "smooth", "birch", "scaly", "plated", "generic"}));
  k.bark_color = t.vec3("bark_color", d.bark_color, 0.0, 1.0);
  k.leaf_color = t.vec3("leaf_color", d.leaf_color, 0.0, 1.0);
  // 3 sides is the least that encloses a tube; 32 is round at any distance the forest shows.
  k.ring_sides_min = int(t.integer("ring_sides_min", d.ring_sides_min, 3, 32));
  k.ring_sides_max = int(t.integer("ring_sides_max", d.ring_sides_max, 3, 32));
  if (k.ring_sides_max < k.ring_sides_min) t.fail("ring_sides_max", "must be >= ring_sides_min");
  return k;
}

}  // namespace forest
