#include "generators/methods/common/image_inputs.h"
#include "generators/core/limits.h"

#include "generators/methods/common/strokes_io.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <OpenImageIO/imageio.h>

#include "generators/core/input_error.h"

namespace forest {

namespace {


std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

[[noreturn]] void fail(const std::string& where, const std::string& key, const std::string& what) {
  throw InputError(where, 0, key, what);
}

// The value of a required key.
const nlohmann::json& required(const nlohmann::json& j, const std::string& key, const std::string& where,
                               const std::string& path) {
  if (!j.contains(key)) fail(where, path + key, "missing required key");
  return j.at(key);
}

double number(const nlohmann::json& j, const std::string& key, const std::string& where,
              const std::string& path, double lo, double hi) {
  const nlohmann::json& v = required(j, key, where, path);
  if (!v.is_number()) fail(where, path + key, "expected a number");
  double d = v.get<double>();
  if (!std::isfinite(d)) fail(where, path + key, "must be finite");
  if (d < lo || d > hi) fail(where, path + key, "must be in [" + fmt(lo) + ", " + fmt(hi) + "], got " + fmt(d));
  return d;
}

int integer(const nlohmann::json& j, const std::string& key, const std::string& where,
            const std::string& path, int lo, int hi) {
  const nlohmann::json& v = required(j, key, where, path);
  if (!v.is_number_integer()) fail(where, path + key, "expected an integer");
  int64_t d = v.get<int64_t>();
  if (d < lo || d > hi) fail(where, path + key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return int(d);
}

std::vector<double> numbers(const nlohmann::json& j, const std::string& key, const std::string& where,
                            const std::string& path, size_t count) {
  const nlohmann::json& v = required(j, key, where, path);
  if (!v.is_array() || v.size() != count)
    fail(where, path + key, "expected an array of " + std::to_string(count) + " numbers");
  std::vector<double> out;
  for (const nlohmann::json& e : v) {
    if (!e.is_number()) fail(where, path + key, "expected an array of " + std::to_string(count) + " numbers");
    double d = e.get<double>();
    if (!std::isfinite(d) || std::abs(d) > 1e9) fail(where, path + key, "values must be finite and below 1e9");
    out.push_back(d);
  }
  return out;
}

glm::dvec3 vec3(const nlohmann::json& j, const std::string& key, const std::string& where,
                const std::string& path) {
  auto v = numbers(j, key, where, path, 3);
  return {v[0], v[1], v[2]};
}

glm::dvec3 vec3_or(const nlohmann::json& j, const std::string& key, const std::string& where,
                   const std::string& path, glm::dvec3 fallback) {
  return j.contains(key) ? vec3(j, key, where, path) : fallback;
}

nlohmann::json to_json(glm::dvec3 v) { return {v.x, v.y, v.z}; }

glm::dvec3 dehomogenize(glm::dvec4 p) { return glm::dvec3(p) / p.w; }

}  // namespace

size_t Mask::count_inside() const {
  size_t n = 0;
  for (float a : alpha) n += a >= 0.5f;
  return n;
}

Camera make_camera(int width, int height, const glm::dmat4& view, const glm::dmat4& proj) {
  Camera c;
  c.width = width;
  c.height = height;
  c.view = view;
  c.proj = proj;
  c.view_proj = proj * view;
  c.inv_view_proj = glm::inverse(c.view_proj);
  // An orthographic projection keeps w = 1: its bottom row is (0, 0, 0, 1).
  c.orthographic = proj[0][3] == 0.0 && proj[1][3] == 0.0 && proj[2][3] == 0.0 && proj[3][3] == 1.0;
  nlohmann::json v = nlohmann::json::array(), p = nlohmann::json::array();
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      v.push_back(view[col][row]);
      p.push_back(proj[col][row]);
    }
  c.spec = {{"type", "matrix"}, {"width", width}, {"height", height}, {"view", v}, {"proj", p}};
  return c;
}

Camera orthographic_camera(int width, int height, glm::dvec3 center, glm::dvec3 direction,
                           glm::dvec3 up, double extent) {
  // The eye sits far behind the centre so that every point of a tree is in front of it.
  constexpr double kBack = 1000.0;
  glm::dvec3 d = glm::normalize(direction);
  glm::dmat4 view = glm::lookAt(center - d * kBack, center, up);
  double hh = 0.5 * extent, hw = hh * double(width) / double(height);
  glm::dmat4 proj = glm::ortho(-hw, hw, -hh, hh, 0.0, 2.0 * kBack);
  Camera c = make_camera(width, height, view, proj);
  c.spec = {{"type", "orthographic"}, {"width", width}, {"height", height},
            {"center", to_json(center)}, {"direction", to_json(direction)},
            {"up", to_json(up)}, {"extent", extent}};
  return c;
}

Camera perspective_camera(int width, int height, glm::dvec3 eye, glm::dvec3 target,
                          glm::dvec3 up, double fov_y_deg) {
  glm::dmat4 view = glm::lookAt(eye, target, up);
  glm::dmat4 proj = glm::perspective(glm::radians(fov_y_deg), double(width) / double(height), 0.01, 1000.0);
  Camera c = make_camera(width, height, view, proj);
  c.spec = {{"type", "perspective"}, {"width", width}, {"height", height}, {"eye", to_json(eye)},
            {"target", to_json(target)}, {"up", to_json(up)}, {"fov_y_deg", fov_y_deg}};
  return c;
}

Projection project(const Camera& c, glm::dvec3 world) {
  glm::dvec4 clip = c.view_proj * glm::dvec4(world, 1.0);
  Projection p;
  p.w = clip.w;
  if (std::abs(clip.w) < 1e-300) return p;
  glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  p.pixel = {(ndc.x + 1.0) * 0.5 * c.width, (1.0 - ndc.y) * 0.5 * c.height};
  return p;
}

Ray pixel_ray(const Camera& c, glm::dvec2 pixel) {
  double x = 2.0 * pixel.x / c.width - 1.0, y = 1.0 - 2.0 * pixel.y / c.height;
  glm::dvec3 n = dehomogenize(c.inv_view_proj * glm::dvec4(x, y, -1.0, 1.0));
  glm::dvec3 f = dehomogenize(c.inv_view_proj * glm::dvec4(x, y, 1.0, 1.0));
  return {n, glm::normalize(f - n)};
}

std::array<glm::dvec3, 2> image_axes(const Camera& c) {
  // Rows of the view rotation are the camera axes in world space.
  glm::dvec3 right(c.view[0][0], c.view[1][0], c.view[2][0]);
  glm::dvec3 up(c.view[0][1], c.view[1][1], c.view[2][1]);
  return {glm::normalize(right), -glm::normalize(up)};
}

Mask load_mask(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail(name, "", "mask file not found");
  {
    // Only PNG and OpenEXR, by signature: OpenImageIO would otherwise hand a file that fails
    // as PNG to every other reader it has (TIFF, DPX, ...), a needless attack surface.
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
    unsigned char head[8] = {};
    std::ifstream probe(file, std::ios::binary);
    probe.read(reinterpret_cast<char*>(head), 8);
    if (!(probe.gcount() == 8 && (std::memcmp(head, kPng, 8) == 0 || std::memcmp(head, kExr, 4) == 0)))
      fail(name, "", "not a PNG or OpenEXR image");
  }
  auto in = OIIO::ImageInput::open(name);
  if (!in) fail(name, "", "not a readable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxImageSide || spec.height > kMaxImageSide ||
      spec.nchannels < 1 || spec.nchannels > 16)
    fail(name, "", "unsupported mask size " + std::to_string(spec.width) + "x" +
                       std::to_string(spec.height) + " (1.." + std::to_string(kMaxImageSide) + " per side)");
  const int nc = spec.nchannels;
  int channel = spec.alpha_channel >= 0 && spec.alpha_channel < nc ? spec.alpha_channel
                : (nc == 2 || nc == 4)                               ? nc - 1
                                                                     : 0;
  // Only the mask channel is read: at most 8192^2 floats (256 MB), whatever the channel count.
  std::vector<float> pixels(size_t(spec.width) * size_t(spec.height));
  if (!in->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::FLOAT, pixels.data()))
    fail(name, "", "corrupt image: " + in->geterror());
  Mask m;
  m.width = spec.width;
  m.height = spec.height;
  m.source = name;
  m.alpha.resize(size_t(m.width) * size_t(m.height));
  for (size_t i = 0; i < m.alpha.size(); ++i) {
    float a = pixels[i];
    if (!std::isfinite(a))
      fail(name, "", "pixel (" + std::to_string(i % size_t(m.width)) + ", " +
                         std::to_string(i / size_t(m.width)) + ") is not a finite number");
    m.alpha[i] = std::min(1.0f, std::max(0.0f, a));
  }
  if (m.count_inside() == 0) fail(name, "", "mask is empty (no pixel with alpha >= 0.5)");
  return m;
}

void write_mask(const Mask& mask, const std::filesystem::path& file) {
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) fail(file.string(), "", "unsupported image format");
  OIIO::ImageSpec spec(mask.width, mask.height, 1, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> bytes(mask.alpha.size());
  for (size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = uint8_t(std::lround(std::min(1.0f, std::max(0.0f, mask.alpha[i])) * 255.0f));
  if (!(out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) && out->close()))
    fail(file.string(), "", "cannot write mask: " + out->geterror());
}

Camera parse_camera(const nlohmann::json& j, const std::string& where, const std::string& key) {
  const std::string path = key + ".";
  if (!j.is_object()) fail(where, key, "expected an object");
  std::string type = j.contains("type") && j["type"].is_string() ? j["type"].get<std::string>()
                     : (j.contains("view") && j.contains("proj")) ? "matrix"
                                                                  : "";
  if (j.contains("type") && !j["type"].is_string()) fail(where, path + "type", "expected a string");
  int w = integer(j, "width", where, path, 1, kMaxImageSide);
  int h = integer(j, "height", where, path, 1, kMaxImageSide);
  Camera c;
  if (type == "matrix") {
    auto v = numbers(j, "view", where, path, 16), p = numbers(j, "proj", where, path, 16);
    glm::dmat4 view, proj;
    for (int k = 0; k < 16; ++k) {
      view[k / 4][k % 4] = v[size_t(k)];
      proj[k / 4][k % 4] = p[size_t(k)];
    }
    if (std::abs(glm::determinant(proj * view)) < 1e-300) fail(where, path + "proj", "view * proj is singular");
    c = make_camera(w, h, view, proj);
  } else if (type == "orthographic") {
    glm::dvec3 center = vec3(j, "center", where, path), dir = vec3(j, "direction", where, path);
    glm::dvec3 up = vec3_or(j, "up", where, path, {0, 1, 0});
    double extent = number(j, "extent", where, path, 1e-6, 1e6);
    if (glm::length(dir) < 1e-9) fail(where, path + "direction", "must not be the zero vector");
    if (glm::length(glm::cross(glm::normalize(dir), up)) < 1e-6) fail(where, path + "up", "must not be parallel to direction");
    c = orthographic_camera(w, h, center, dir, up, extent);
  } else if (type == "perspective") {
    glm::dvec3 eye = vec3(j, "eye", where, path), target = vec3(j, "target", where, path);
    glm::dvec3 up = vec3_or(j, "up", where, path, {0, 1, 0});
    double fov = number(j, "fov_y_deg", where, path, 0.1, 170.0);
    if (glm::length(target - eye) < 1e-9) fail(where, path + "target", "must differ from eye");
    if (glm::length(glm::cross(glm::normalize(target - eye), up)) < 1e-6) fail(where, path + "up", "must not be parallel to the view direction");
    c = perspective_camera(w, h, eye, target, up, fov);
  } else {
    fail(where, path + "type", "expected \"orthographic\", \"perspective\" or \"matrix\"");
  }
  return c;
}

nlohmann::json camera_to_json(const Camera& camera) { return camera.spec; }

ViewSet load_view_set(const std::filesystem::path& file) {
  const std::string where = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) fail(where, "", "views file not found");
  std::ifstream in(file, std::ios::binary);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail(where, "", std::string("malformed JSON: ") + e.what());
  }
  if (!j.is_object()) fail(where, "", "expected a JSON object");
  for (auto& [key, value] : j.items())
    if (key != "bounds" && key != "base" && key != "views")
      fail(where, key, "unknown key (expected bounds, base, views)");
  ViewSet set;
  set.source = where;
  if (!j.contains("bounds") || !j["bounds"].is_object()) fail(where, "bounds", "missing required object");
  set.bounds.min = vec3(j["bounds"], "min", where, "bounds.");
  set.bounds.max = vec3(j["bounds"], "max", where, "bounds.");
  glm::dvec3 size = set.bounds.size();
  if (!(size.x > 0 && size.y > 0 && size.z > 0)) fail(where, "bounds.max", "must exceed bounds.min on every axis");
  set.base = vec3_or(j, "base", where, "",
                     {0.5 * (set.bounds.min.x + set.bounds.max.x), set.bounds.min.y,
                      0.5 * (set.bounds.min.z + set.bounds.max.z)});
  if (!j.contains("views") || !j["views"].is_array() || j["views"].empty())
    fail(where, "views", "expected a non-empty array of views");
  if (j["views"].size() > 64) fail(where, "views", "at most 64 views");
  const std::filesystem::path dir = file.parent_path();
  for (size_t k = 0; k < j["views"].size(); ++k) {
    const nlohmann::json& v = j["views"][k];
    const std::string path = "views[" + std::to_string(k) + "].";
    if (!v.is_object()) fail(where, path.substr(0, path.size() - 1), "expected an object");
    for (auto& [key, value] : v.items())
      if (key != "mask" && key != "camera" && key != "attractors")
        fail(where, path + key, "unknown key (expected mask, camera, attractors)");
    if (!v.contains("mask") || !v["mask"].is_string()) fail(where, path + "mask", "missing mask file name");
    if (!v.contains("camera")) fail(where, path + "camera", "missing camera pose");
    View view;
    view.mask = load_mask(dir / v["mask"].get<std::string>());
    view.camera = parse_camera(v["camera"], where, path + "camera");
    if (view.camera.width != view.mask.width || view.camera.height != view.mask.height)
      fail(where, path + "camera.width",
           "camera size " + std::to_string(view.camera.width) + "x" + std::to_string(view.camera.height) +
               " differs from mask " + view.mask.source + " (" + std::to_string(view.mask.width) + "x" +
               std::to_string(view.mask.height) + ")");
    if (v.contains("attractors") && v["attractors"].is_string()) {
      // An SVG drawing in pixel coordinates (its y axis is the image's v axis).
      std::filesystem::path svg = dir / v["attractors"].get<std::string>();
      if (svg.extension() != ".svg") fail(where, path + "attractors", "expected an array of polylines or an .svg file");
      Drawing drawing = read_drawing(svg);
      for (const Stroke& stroke : drawing.strokes) {
        Polyline2 line;
        for (glm::dvec2 q : stroke.points) line.push_back({q.x, -q.y});
        view.attractors.push_back(std::move(line));
      }
    } else if (v.contains("attractors")) {
      const nlohmann::json& a = v["attractors"];
      if (!a.is_array() || a.size() > 10000) fail(where, path + "attractors", "expected an array of polylines");
      for (size_t p = 0; p < a.size(); ++p) {
        const std::string ppath = path + "attractors[" + std::to_string(p) + "]";
        if (!a[p].is_array() || a[p].size() < 2 || a[p].size() > 100000)
          fail(where, ppath, "a polyline needs at least 2 points [u, v]");
        Polyline2 line;
        for (const nlohmann::json& pt : a[p]) {
          if (!pt.is_array() || pt.size() != 2 || !pt[0].is_number() || !pt[1].is_number())
            fail(where, ppath, "points must be [u, v] pairs of numbers");
          glm::dvec2 q(pt[0].get<double>(), pt[1].get<double>());
          if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::abs(q.x) > 1e6 || std::abs(q.y) > 1e6)
            fail(where, ppath, "points must be finite pixel coordinates");
          line.push_back(q);
        }
        view.attractors.push_back(std::move(line));
      }
    }
    set.views.push_back(std::move(view));
  }
  return set;
}

void write_view_set(const ViewSet& set, const std::filesystem::path& dir, bool svg_attractors) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) fail(dir.string(), "", "cannot create folder: " + ec.message());
  nlohmann::json j;
  j["bounds"] = {{"min", to_json(set.bounds.min)}, {"max", to_json(set.bounds.max)}};
  j["base"] = to_json(set.base);
  j["views"] = nlohmann::json::array();
  for (size_t k = 0; k < set.views.size(); ++k) {
    const View& v = set.views[k];
    std::string name = "view" + std::to_string(k) + ".png";
    write_mask(v.mask, dir / name);
    nlohmann::json jv = {{"mask", name}, {"camera", camera_to_json(v.camera)}};
    if (!v.attractors.empty()) {
      nlohmann::json lines = nlohmann::json::array();
      for (const Polyline2& line : v.attractors) {
        nlohmann::json pts = nlohmann::json::array();
        // Rounded to 1/100 pixel: readable files, nothing a pixel grid can resolve is lost.
        for (glm::dvec2 p : line) pts.push_back({std::round(p.x * 100.0) / 100.0, std::round(p.y * 100.0) / 100.0});
        lines.push_back(pts);
      }
      jv["attractors"] = lines;
    }
    j["views"].push_back(jv);
  }
  std::ofstream out(dir / "views.json", std::ios::binary);
  out << j.dump(1) << "\n";
  if (!out) fail((dir / "views.json").string(), "", "cannot write");
  // The same view set with the attractors as SVG drawings (one per view, pixel coordinates):
  // the form a user draws over a photo in a vector editor.
  bool any = false;
  for (size_t k = 0; k < set.views.size(); ++k) {
    const View& v = set.views[k];
    if (!svg_attractors || v.attractors.empty()) continue;
    any = true;
    Drawing drawing;
    for (size_t l = 0; l < v.attractors.size(); ++l) {
      Stroke stroke;
      stroke.id = "attractor" + std::to_string(l);
      stroke.role = "attractor";
      for (glm::dvec2 p : v.attractors[l])
        stroke.points.push_back({std::round(p.x * 100.0) / 100.0, -(std::round(p.y * 100.0) / 100.0)});
      drawing.strokes.push_back(std::move(stroke));
    }
    std::string name = "view" + std::to_string(k) + "_attractors.svg";
    std::ofstream svg(dir / name, std::ios::binary);
    svg << drawing_to_svg(drawing);
    if (!svg) fail((dir / name).string(), "", "cannot write");
    j["views"][k]["attractors"] = name;
  }
  if (any) {
    std::ofstream out_svg(dir / "views_svg.json", std::ios::binary);
    out_svg << j.dump(1) << "\n";
    if (!out_svg) fail((dir / "views_svg.json").string(), "", "cannot write");
  }
}

}  // namespace forest
