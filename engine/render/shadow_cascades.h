// Cascaded shadow maps of the sun (Engel, "Cascaded shadow maps", ShaderX5 2006; Zhang et
// al., "Parallel-split shadow maps", 2006): the camera's view depths [near, distance] split
// into SHADOW_CASCADES slices, each covered by an orthographic sun camera. Stabilized the way
// production renderers do it (Valient, "Stable rendering of cascaded shadow maps", ShaderX6
// 2008): each cascade is the bounding sphere of its frustum slice, whose radius does not
// change as the camera turns; the sun camera's rotation depends on the sun alone, and its
// centre is snapped to whole texels, so a moving camera slides the shadow map by whole texels
// and shadow edges do not crawl. Pure CPU math, O(1) per frame.
#pragma once
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/scene/camera.h"
#include "gpu_types.h"

namespace forest {

struct ShadowCascade {
  glm::mat4 view_proj{1.0f};          // world → [-1, 1]² × [0, 1] (0 toward the sun)
  std::array<glm::vec4, 6> planes{};  // caster volume, inward normals as CameraMatrices::frustum
  float split_far = 0.0f;             // view depth (m) where the cascade ends
  float texel = 0.0f;                 // world size of one shadow-map texel (m)
  glm::vec3 center{0.0f};             // snapped centre of the covering sphere
  float radius = 0.0f;
};

struct ShadowCascades {
  std::array<ShadowCascade, SHADOW_CASCADES> cascades{};
  float distance = 0.0f;
};

// Caster bounds: an axis-aligned box holding everything that may cast (terrain and trees).
struct ShadowBounds {
  glm::vec3 min{-1.0f}, max{1.0f};
};

// Fraction of the practical split scheme (Zhang et al. 2006) that is logarithmic; the rest is
// uniform. Splits start at kShadowSplitNear (a camera near plane of 0.1 m would make the
// logarithmic first slice centimetres deep).
inline constexpr float kShadowSplitLog = 0.75f;
inline constexpr float kShadowSplitNear = 1.0f;

// Texels per cascade side for a frame `height` pixels tall when the scene names none: the
// power of two at or above 2 × height, within [512, 4096] (720 p: 2048, 360 p: 1024). A
// cascade's texel then stays within about 1.5 camera pixels at its slice's near end, and the
// casters' detail follows (shadow_cull.comp prunes to the PCF footprint): a fixed 2048 at
// 360 p rendered shadow detail twice as fine as any pixel shows, at the cost of per-caster
// triangles, which is what lavapipe pays for.
uint32_t shadow_resolution_for(uint32_t height);

// `sun` points toward the sun (unit). `resolution`: texels per side of each cascade.
ShadowCascades compute_shadow_cascades(const CameraDesc& camera, float aspect, glm::vec3 sun, float distance,
                                       uint32_t resolution, const ShadowBounds& bounds);

}  // namespace forest
