// Camera paths: named keyframe sequences played by `forest render --path`, `forest bench`
// and `forest walk`. Positions and targets follow centripetal Catmull-Rom splines through
// the keys (no cusps or self-intersections between close keys); the camera looks at the
// interpolated target, so orientation needs no quaternion bookkeeping.
#pragma once
#include <string>
#include <vector>

#include "engine/scene/scene_file.h"

namespace forest {

// camera_at() evaluates a path at time t (seconds). Times before the first key clamp to it,
// after the last clamp to it (or wrap when the path loops). fov is interpolated linearly;
// near and far come from `base` (the scene's [camera]).
CameraDesc camera_at(const CameraPath& path, float t, const CameraDesc& base);

// Seconds from the first to the last key.
float path_duration(const CameraPath& path);

// The path named `name`, or nullptr.
const CameraPath* find_path(const SceneDesc& scene, const std::string& name);

// Centripetal Catmull-Rom (α = 1/2) between p1 and p2 at u ∈ [0, 1], p0 and p3 the
// neighbours (Barry-Goldman pyramid; knot spacing |p_i+1 − p_i|^½).
glm::vec3 centripetal_catmull_rom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float u);

}  // namespace forest
