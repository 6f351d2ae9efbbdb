// Scene files from text in the unit tests: parsed as "s.toml" in scenes/ (where presets are
// found), and the one-line message of the InputError a text raises.
#pragma once
#include <string>

#include "engine/scene/scene_file.h"
#include "generators/core/input_error.h"

namespace forest::test {

inline const std::string kScenes = std::string(FOREST_SOURCE_DIR) + "/scenes";

inline SceneDesc parse(const std::string& text) { return parse_scene_text(text, "s.toml", kScenes); }

// The message of the InputError that parsing `text` raises; empty when it parses.
inline std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace forest::test
