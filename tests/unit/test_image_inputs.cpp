// Image inputs: cameras, masks (PNG/EXR), views.json, synthetic masks and attractors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "generators/core/input_error.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/methods/common/image_synthetic.h"
#include "tests/common/test_files.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) { return test::fresh_temp_dir("forest_image_inputs", name); }

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// Expects `fn` to throw an InputError whose one-line message contains every fragment.
template <class Fn>
void expect_input_error(Fn&& fn, std::initializer_list<std::string> fragments) {
  try {
    fn();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    for (const std::string& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << " lacks " << f;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
}

Mask disc_mask(int size, double r) {
  Mask m;
  m.width = m.height = size;
  m.alpha.assign(size_t(size) * size_t(size), 0.0f);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      if (std::hypot(i + 0.5 - size / 2.0, j + 0.5 - size / 2.0) < r) m.alpha[size_t(j * size + i)] = 1.0f;
  return m;
}

}  // namespace

TEST(ImageInputs, PixelRaysProjectBackToTheirPixel) {
  std::vector<Camera> cams = {
      orthographic_camera(160, 120, {1, 2, 3}, {0.3, -0.2, -1}, {0, 1, 0}, 7.0),
      perspective_camera(160, 120, {10, 4, 12}, {0, 3, 0}, {0, 1, 0}, 40.0)};
  for (const Camera& c : cams)
    for (glm::dvec2 px : {glm::dvec2(0.5, 0.5), glm::dvec2(80, 60), glm::dvec2(159.2, 3.7)}) {
      Ray r = pixel_ray(c, px);
      for (double t : {1.0, 10.0, 25.0}) {
        Projection p = project(c, r.origin + r.direction * t);
        EXPECT_TRUE(p.in_front());
        EXPECT_NEAR(p.pixel.x, px.x, 1e-6);
        EXPECT_NEAR(p.pixel.y, px.y, 1e-6);
      }
    }
}

TEST(ImageInputs, OrthographicCameraFramesItsExtent) {
  // Looking along -Z with up +Y: world +X is image right, world +Y is image up (v down).
  Camera c = orthographic_camera(100, 100, {0, 5, 0}, {0, 0, -1}, {0, 1, 0}, 10.0);
  EXPECT_TRUE(c.orthographic);
  Projection centre = project(c, {0, 5, 0}), top_right = project(c, {5, 10, 0});
  EXPECT_NEAR(centre.pixel.x, 50.0, 1e-9);
  EXPECT_NEAR(centre.pixel.y, 50.0, 1e-9);
  EXPECT_NEAR(top_right.pixel.x, 100.0, 1e-9);
  EXPECT_NEAR(top_right.pixel.y, 0.0, 1e-9);
  auto axes = image_axes(c);
  EXPECT_NEAR(glm::length(axes[0] - glm::dvec3(1, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(axes[1] - glm::dvec3(0, -1, 0)), 0.0, 1e-12);
  EXPECT_FALSE(perspective_camera(10, 10, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30).orthographic);
}

TEST(ImageInputs, MaskRoundTripAndDeterministicBytes) {
  fs::path d = temp_dir("roundtrip");
  Mask m = disc_mask(64, 20);
  write_mask(m, d / "a.png");
  write_mask(m, d / "b.png");
  EXPECT_EQ(test::slurp(d / "a.png"), test::slurp(d / "b.png"));
  EXPECT_LT(fs::file_size(d / "a.png"), 4096u);
  Mask back = load_mask(d / "a.png");
  ASSERT_EQ(back.width, 64);
  ASSERT_EQ(back.height, 64);
  EXPECT_EQ(back.alpha, m.alpha);
  fs::remove_all(d);
}

TEST(ImageInputs, AlphaChannelIsTheMaskWhenPresent) {
  fs::path d = temp_dir("alpha");
  // RGBA: colour everywhere, alpha only in the left half.
  std::vector<uint8_t> px(8 * 4 * 4, 200);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i) px[size_t((j * 8 + i) * 4 + 3)] = i < 4 ? 255 : 0;
  auto out = OIIO::ImageOutput::create((d / "rgba.png").string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(8, 4, 4, OIIO::TypeDesc::UINT8);
  spec.alpha_channel = 3;
  ASSERT_TRUE(out->open((d / "rgba.png").string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, px.data()) && out->close());
  Mask m = load_mask(d / "rgba.png");
  EXPECT_EQ(m.count_inside(), 16u);
  EXPECT_TRUE(m.inside(0, 0));
  EXPECT_FALSE(m.inside(7, 3));
  fs::remove_all(d);
}

TEST(ImageInputs, BadMasksNameTheFile) {
  fs::path d = temp_dir("bad");
  expect_input_error([&] { load_mask(d / "missing.png"); }, {"missing.png", "not found"});
  write_text(d / "corrupt.png", "\x89PNG\r\n\x1a\n this is not a png");
  expect_input_error([&] { load_mask(d / "corrupt.png"); }, {"corrupt.png"});
  Mask empty;
  empty.width = empty.height = 16;
  empty.alpha.assign(256, 0.2f);
  write_mask(empty, d / "empty.png");
  expect_input_error([&] { load_mask(d / "empty.png"); }, {"empty.png", "empty"});
  // NaN in a float EXR.
  std::vector<float> f(16, 1.0f);
  f[5] = std::nanf("");
  auto out = OIIO::ImageOutput::create((d / "nan.exr").string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(4, 4, 1, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open((d / "nan.exr").string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, f.data()) && out->close());
  expect_input_error([&] { load_mask(d / "nan.exr"); }, {"nan.exr", "(1, 1)", "finite"});
  fs::remove_all(d);
}

TEST(ImageInputs, ViewSetRoundTrip) {
  fs::path d = temp_dir("viewset");
  CrownSpec spec;
  spec.resolution = 64;
  spec.branches = 3;
  ViewSet set = synthesize_view_set(spec);
  write_view_set(set, d);
  ViewSet back = load_view_set(d / "views.json");
  ASSERT_EQ(back.views.size(), set.views.size());
  for (size_t k = 0; k < set.views.size(); ++k) {
    EXPECT_EQ(back.views[k].mask.alpha, set.views[k].mask.alpha);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(back.views[k].camera.view_proj[c][r], set.views[k].camera.view_proj[c][r], 1e-9);
    ASSERT_EQ(back.views[k].attractors.size(), set.views[k].attractors.size());
    EXPECT_NEAR(back.views[k].attractors[1][2].x, set.views[k].attractors[1][2].x, 0.006);
  }
  EXPECT_EQ(back.bounds.max, set.bounds.max);
  fs::remove_all(d);
}

TEST(ImageInputs, BadViewSetsNameFileAndKey) {
  fs::path d = temp_dir("badviews");
  write_mask(disc_mask(32, 10), d / "m.png");
  const std::string cam = R"({"type": "orthographic", "width": 32, "height": 32, "center": [0, 1, 0], "direction": [0, 0, -1], "extent": 2})";
  auto views = [&](const std::string& body) {
    write_text(d / "views.json", R"({"bounds": {"min": [-1, 0, -1], "max": [1, 2, 1]}, "views": [)" + body + "]}");
    return d / "views.json";
  };
  expect_input_error([&] { load_view_set(views(R"({"mask": "m.png"})")); }, {"views.json", "views[0].camera", "missing"});
  std::string small = cam;
  small.replace(small.find("\"width\": 32"), 11, "\"width\": 16");
  expect_input_error([&] { load_view_set(views(R"({"mask": "m.png", "camera": )" + small + "}")); },
                     {"views.json", "views[0].camera.width", "differs"});
  expect_input_error([&] { load_view_set(views(R"({"mask": "nope.png", "camera": )" + cam + "}")); }, {"nope.png", "not found"});
  std::string bad_dir = cam;
  bad_dir.replace(bad_dir.find("[0, 0, -1]"), 10, "[0, 0, 0]");
  expect_input_error([&] { load_view_set(views(R"({"mask": "m.png", "camera": )" + bad_dir + "}")); },
                     {"views[0].camera.direction"});
  expect_input_error([&] { load_view_set(views(R"({"mask": "m.png", "camera": )" + cam + R"(, "attractors": [[[1, 2]]]})")); },
                     {"views[0].attractors[0]"});
  write_text(d / "views.json", "{ not json");
  expect_input_error([&] { load_view_set(d / "views.json"); }, {"views.json", "malformed JSON"});
  write_text(d / "views.json", R"({"bounds": {"min": [0, 0, 0], "max": [0, 2, 1]}, "views": []})");
  expect_input_error([&] { load_view_set(d / "views.json"); }, {"bounds.max"});
  fs::remove_all(d);
}

TEST(ImageInputs, SyntheticEllipsoidMaskHasTheEllipseArea) {
  CrownSpec spec;
  spec.shape = "ellipsoid";
  spec.trunk_radius = 0.0;
  spec.resolution = 256;
  SyntheticTree tree = make_synthetic_tree(spec);
  Camera c = synthetic_cameras(tree, spec)[0];
  Mask m = render_mask(tree, c);
  // Front view (orthographic): an ellipse with semi-axes width/2 and crown height/2.
  double px_per_m = 256.0 / c.spec["extent"].get<double>();
  double expected = 3.14159265358979 * 0.5 * spec.width * 0.5 * (spec.height - spec.trunk_height) * px_per_m * px_per_m;
  EXPECT_NEAR(double(m.count_inside()), expected, 0.01 * expected);
}

TEST(ImageInputs, SyntheticAttractorsLieOnTheSilhouette) {
  CrownSpec spec;
  spec.shape = "lobes";
  spec.views = 4;
  spec.perspective = true;
  ViewSet set = synthesize_view_set(spec);
  for (const View& v : set.views) {
    ASSERT_EQ(v.attractors.size(), size_t(1 + spec.branches));
    for (const Polyline2& line : v.attractors)
      for (glm::dvec2 p : line) {
        // Within a pixel of the silhouette (the foot sits on its bottom edge).
        bool near = false;
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) near = near || v.mask.inside(int(p.x) + di, int(p.y) + dj);
        EXPECT_TRUE(near) << p.x << " " << p.y;
      }
  }
}
