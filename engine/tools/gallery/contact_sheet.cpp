#include "engine/tools/gallery/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <glm/gtc/constants.hpp>

namespace forest {

namespace {
constexpr uint8_t kBackground = 40;  // the sheet's neutral grey
}

Scene make_model_scene(const TreeModel& model, uint32_t size, uint32_t samples) {
  float radius = std::max(model.bounding_sphere.w, 1e-3f);
  Scene scene;
  scene.desc.width = scene.desc.height = size;
  scene.desc.samples = samples;
  scene.desc.lod_error_pixels = 0.0f;  // a preview shows full detail
  scene.desc.sky.fog_density = 0.0f;
  scene.desc.terrain.size = std::max(radius * 8.0f, 10.0f);
  scene.desc.terrain.resolution = 4;
  scene.desc.terrain.height = 0.0f;
  scene.desc.trees.push_back(TreeDesc{});
  scene.terrain = make_terrain(scene.desc.terrain);
  scene.models.push_back(model);
  scene.instances = place_trees(scene.desc, scene.terrain);
  return scene;
}

CameraDesc orbit_camera(glm::vec4 sphere, float azimuth, float elevation, float fov_deg) {
  float distance = std::max(sphere.w, 1e-3f) / std::sin(glm::radians(fov_deg) * 0.5f) * 1.05f;
  CameraDesc cam;
  cam.target = glm::vec3(sphere);
  cam.position = cam.target + distance * glm::vec3(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                                   -std::cos(azimuth) * std::cos(elevation));
  cam.fov_deg = fov_deg;
  cam.near = std::max(distance * 1e-3f, 1e-3f);
  cam.far = distance * 4.0f;
  return cam;
}

std::vector<FrameImage> render_turntable(vk::Context& ctx, const TreeModel& model, const TurntableOptions& options) {
  Scene scene = make_model_scene(model, options.size, options.samples);
  Renderer renderer(ctx, scene, options.size, options.size, options.samples);
  std::vector<FrameImage> frames;
  for (uint32_t v = 0; v < options.views; ++v) {
    float azimuth = 2.0f * glm::pi<float>() * float(v) / float(options.views);
    CameraDesc cam = orbit_camera(model.bounding_sphere, azimuth, glm::radians(options.elevation_deg), options.fov_deg);
    FrameImage image;
    renderer.render(cam, &image, options.settings);
    frames.push_back(std::move(image));
  }
  return frames;
}

FrameImage add_label(const FrameImage& frame, const std::vector<std::string>& lines, uint32_t band) {
  FrameImage out;
  out.width = frame.width;
  out.height = frame.height + band;
  out.rgba.resize(size_t(out.width) * out.height * 4);
  std::memcpy(out.rgba.data(), frame.rgba.data(), frame.rgba.size());
  for (size_t i = frame.rgba.size(); i < out.rgba.size(); i += 4) {
    out.rgba[i] = out.rgba[i + 1] = out.rgba[i + 2] = kBackground;
    out.rgba[i + 3] = 255;
  }
  // OIIO draws straight into our pixels (the plots of `forest report` use the same text).
  OIIO::ImageBuf buf(OIIO::ImageSpec(int(out.width), int(out.height), 4, OIIO::TypeDesc::UINT8), out.rgba.data());
  const int big = std::max(8, int(band * 0.42f)), small = std::max(7, int(band * 0.3f));
  const float white[4] = {1, 1, 1, 1}, grey[4] = {0.7f, 0.7f, 0.7f, 1};
  int y = int(frame.height) + big + std::max(1, int(band) / 16);
  for (size_t i = 0; i < lines.size(); ++i) {
    int px = i == 0 ? big : small;
    if (y > int(out.height)) break;
    OIIO::ImageBufAlgo::render_text(buf, std::max(2, px / 3), y, lines[i], px, "DejaVuSans", i == 0 ? white : grey);
    y += small + std::max(2, px / 4);
  }
  return out;
}

FrameImage compose_grid(const std::vector<FrameImage>& frames, uint32_t columns, uint32_t gap) {
  FrameImage sheet;
  if (frames.empty()) return sheet;
  columns = std::max(1u, std::min(columns, uint32_t(frames.size())));
  uint32_t rows = uint32_t((frames.size() + columns - 1) / columns);
  uint32_t w = frames[0].width, h = frames[0].height;
  sheet.width = columns * w + (columns + 1) * gap;
  sheet.height = rows * h + (rows + 1) * gap;
  sheet.rgba.assign(size_t(sheet.width) * sheet.height * 4, 0);
  for (size_t i = 0; i < sheet.rgba.size(); i += 4) {  // neutral grey background
    sheet.rgba[i] = sheet.rgba[i + 1] = sheet.rgba[i + 2] = kBackground;
    sheet.rgba[i + 3] = 255;
  }
  for (size_t i = 0; i < frames.size(); ++i) {
    uint32_t x0 = gap + uint32_t(i % columns) * (w + gap), y0 = gap + uint32_t(i / columns) * (h + gap);
    for (uint32_t y = 0; y < h; ++y)
      std::memcpy(&sheet.rgba[(size_t(y0 + y) * sheet.width + x0) * 4], frames[i].pixel(0, y), size_t(w) * 4);
  }
  return sheet;
}

}  // namespace forest
