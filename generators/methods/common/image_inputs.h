// Image inputs shared by the image-based methods (particle-flow, visual-hull): silhouette
// masks (PNG/EXR through OpenImageIO), camera poses and attractor polylines (JSON).
//
// A view set is one JSON file ("views.json"); relative paths in it resolve against its folder:
//   {
//     "bounds": {"min": [x, y, z], "max": [x, y, z]},   // world box that holds the tree
//     "base": [x, y, z],                                 // optional tree foot; default: the
//                                                        // centre of the bottom face of bounds
//     "views": [
//       { "mask": "front.png",                           // PNG or EXR, any bit depth
//         "camera": { ... },                             // one of the forms below
//         "attractors": [ [[u, v], [u, v], ...], ... ] } // optional polylines, pixels, or
//                                                        // "file.svg": an SVG drawing in pixel
//                                                        // coordinates (strokes_io.h subset),
//                                                        // one polyline per stroke
//     ]
//   }
// Masks: the alpha channel when the image has one, else the first channel; values in [0, 1]
// (1 = tree). A pixel belongs to the silhouette when alpha >= 0.5.
// Pixels: u to the right, v down, pixel (i, j) covers [i, i+1) x [j, j+1), row 0 is the top
// row of the image file.
// Attractor polylines (Neubert 2012 ch3: trunk and first-order branches drawn on the photo) run
// from their root end toward their tip; the tangent "toward the root" is therefore the
// direction from a point to its predecessor.
// Cameras (world: meters, +Y up; all forms must give the mask's width and height):
//   {"type": "matrix", "width": W, "height": H, "view": [16], "proj": [16]}
//       OpenGL convention, column-major, NDC x right / y up / z in [-1, 1]; "type" may be
//       omitted when "view" and "proj" are present.
//   {"type": "orthographic", "width": W, "height": H, "center": [x, y, z],
//    "direction": [dx, dy, dz], "up": [0, 1, 0], "extent": E}
//       looks along `direction` through `center` (image centre); E = world height covered by
//       the image (its width covers E * W / H).
//   {"type": "perspective", "width": W, "height": H, "eye": [x, y, z],
//    "target": [x, y, z], "up": [0, 1, 0], "fov_y_deg": F}
#pragma once
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace forest {

struct Mask {
  int width = 0;
  int height = 0;
  std::vector<float> alpha;  // row-major, row 0 at the top, values in [0, 1]
  std::string source;        // file name (for messages)

  float at(int i, int j) const { return alpha[size_t(j) * size_t(width) + size_t(i)]; }
  // Silhouette membership of pixel (i, j); false outside the image.
  bool inside(int i, int j) const {
    return i >= 0 && j >= 0 && i < width && j < height && at(i, j) >= 0.5f;
  }
  size_t count_inside() const;
};

struct Camera {
  int width = 0;
  int height = 0;
  glm::dmat4 view{1.0};
  glm::dmat4 proj{1.0};
  glm::dmat4 view_proj{1.0};      // proj * view
  glm::dmat4 inv_view_proj{1.0};  // its inverse (pixel rays)
  bool orthographic = true;
  nlohmann::json spec;  // the JSON form it was made from (written back by write_view_set)
};

// A camera from its view and projection matrices (fills the derived members).
Camera make_camera(int width, int height, const glm::dmat4& view, const glm::dmat4& proj);
Camera orthographic_camera(int width, int height, glm::dvec3 center, glm::dvec3 direction,
                           glm::dvec3 up, double extent);
Camera perspective_camera(int width, int height, glm::dvec3 eye, glm::dvec3 target,
                          glm::dvec3 up, double fov_y_deg);

// World point -> continuous pixel coordinates (u, v) and the clip w (> 0 when in front of a
// perspective camera; 1 for orthographic).
struct Projection {
  glm::dvec2 pixel{0.0};
  double w = 1.0;
  bool in_front() const { return w > 1e-12; }
};
Projection project(const Camera& camera, glm::dvec3 world);

// The ray through continuous pixel (u, v): origin on the near plane, unit direction.
struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};
};
Ray pixel_ray(const Camera& camera, glm::dvec2 pixel);

// World directions of the image axes: +u (right) and +v (down), unit length (the camera's
// own axes). Lifts 2D image directions to 3D: exact for orthographic cameras, and within the
// half field of view for perspective ones (the seed method assumes near-orthographic photos).
std::array<glm::dvec3, 2> image_axes(const Camera& camera);

using Polyline2 = std::vector<glm::dvec2>;

struct View {
  Mask mask;
  Camera camera;
  std::vector<Polyline2> attractors;  // pixels, root end first
};

struct Bounds {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
  glm::dvec3 size() const { return max - min; }
};

struct ViewSet {
  std::vector<View> views;
  Bounds bounds;
  glm::dvec3 base{0.0};
  std::string source;  // the views.json path or a description of synthetic input
};

// Masks: missing / unreadable / corrupt file, NaN or infinite values, an empty mask (no pixel
// >= 0.5) or absurd sizes -> InputError naming the file.
Mask load_mask(const std::filesystem::path& file);
// 8-bit grey PNG (or any format OpenImageIO writes, by extension); deterministic bytes.
void write_mask(const Mask& mask, const std::filesystem::path& file);

// A camera from JSON (forms above); messages name the file `where` and the JSON path `key`.
Camera parse_camera(const nlohmann::json& j, const std::string& where,
                    const std::string& key = "camera");
nlohmann::json camera_to_json(const Camera& camera);

// views.json -> masks, cameras, attractors. Errors: missing file, bad JSON, missing or wrong
// keys (named by JSON path), a camera size that differs from its mask, NaN anywhere, empty
// polylines, bounds with max <= min, no views.
ViewSet load_view_set(const std::filesystem::path& views_json);
// Writes views.json + one PNG per view (view0.png, ...) into `dir` (created); with
// `svg_attractors` also viewK_attractors.svg and views_svg.json, the same set referring to them.
void write_view_set(const ViewSet& set, const std::filesystem::path& dir, bool svg_attractors = false);

}  // namespace forest
