// Turntable views of one model on a neutral ground, and grids of frames (contact sheets):
// `forest preview`, `forest gallery`, and tests that need to see a model.
#pragma once
#include <string>
#include <vector>

#include "engine/render/renderer.h"

namespace forest {

struct TurntableOptions {
  uint32_t size = 384;        // pixels per view (square)
  uint32_t views = 4;         // evenly spaced azimuths
  float elevation_deg = 12.0f;
  float fov_deg = 30.0f;
  uint32_t samples = 4;
  FrameSettings settings;  // e.g. impostors always: the impostor in place of the mesh
};

// A scene holding just `model` at the origin on a flat neutral ground, no fog.
Scene make_model_scene(const TreeModel& model, uint32_t size, uint32_t samples);
// A camera on a sphere around the model's bounding sphere that frames it.
CameraDesc orbit_camera(glm::vec4 bounding_sphere, float azimuth_rad, float elevation_rad, float fov_deg);

// One frame per view, the camera framing the model's bounding sphere.
std::vector<FrameImage> render_turntable(vk::Context& ctx, const TreeModel& model, const TurntableOptions& options);

// `frame` with a band of `band` pixels added below it (the sheet's background grey) holding
// `lines` of text, the first larger and white, the rest grey (OpenImageIO, DejaVu Sans).
FrameImage add_label(const FrameImage& frame, const std::vector<std::string>& lines, uint32_t band);

// Frames (all the same size) laid out left to right, top to bottom, `columns` wide, with a
// `gap` of background color between them.
FrameImage compose_grid(const std::vector<FrameImage>& frames, uint32_t columns, uint32_t gap = 4);

}  // namespace forest
