// Method `magnetic` (Xu 2015 ch7): Lorentz-force curves, space filling, relief model, SVG.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/methods/magnetic/magnetic_curves.h"
#include "generators/methods/magnetic/magnetic_method.h"
#include "generators/species/registry.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

fs::path species(const std::string& name) {
  return fs::path(FOREST_SOURCE_DIR) / "scenes" / "species" / (name + ".toml");
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Charge constant(double q) {
  Charge c;
  c.profile = ChargeProfile::Constant;
  c.q0 = q;
  return c;
}

}  // namespace

TEST(Magnetic, ZeroChargeFliesStraight) {
  Particle p;
  p.velocity = glm::normalize(glm::dvec3(0.3, 1.0, 0.0));
  auto pts = trace_particle(p, constant(0.0), MagneticField{}, 0.5, 200);
  for (const auto& x : pts) {
    glm::dvec3 d = x - pts[0];
    EXPECT_NEAR(d.x * p.velocity.y - d.y * p.velocity.x, 0.0, 1e-9);
  }
}

TEST(Magnetic, ConstantChargeTracesCircleOfRadiusMvOverQB) {
  for (double q : {0.5, 2.0, -1.0}) {
    MagneticField f;
    f.b0 = 1.5;
    Particle p;
    p.mass = 2.0;
    p.velocity = glm::dvec3(0.0, 3.0, 0.0);
    double r = p.mass * 3.0 / (std::abs(q) * f.b0);
    double dt = 0.002 * r / 3.0;
    auto pts = trace_particle(p, constant(q), f, dt, int(2.0 * 3.14159265 * r / 3.0 / dt));
    // F = q v × B: v = +y, B = +z -> force along +x for q > 0; centre at (±r, 0).
    glm::dvec3 centre(q > 0 ? r : -r, 0.0, 0.0);
    for (const auto& x : pts) EXPECT_NEAR(glm::length(x - centre), r, 0.01 * r) << q;
    // Curvature sign = −sign(q B_z) in the z of v_i × v_{i+1} (clockwise for q B > 0).
    glm::dvec3 v0 = pts[1] - pts[0], v1 = pts[2] - pts[1];
    EXPECT_LT(glm::cross(v0, v1).z * q * f.b0, 0.0);
  }
}

TEST(Magnetic, OppositeChargesMirrorEachOther) {
  Charge c;
  c.profile = ChargeProfile::Spiral;
  c.T = 300;
  c.alpha = 0.75;
  Charge d = c;
  d.sign = -1.0;
  Particle p;
  p.position = glm::dvec3(10.0, 0.0, 0.0);
  auto a = trace_particle(p, c, MagneticField{}, 0.5, 500);
  auto b = trace_particle(p, d, MagneticField{}, 0.5, 500);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].x - 10.0, -(b[i].x - 10.0), 1e-9);
    EXPECT_NEAR(a[i].y, b[i].y, 1e-9);
  }
  // The spiral charge grows: the curve tightens (last quarter turns faster than the first).
  auto turn = [&](size_t i) {
    glm::dvec3 u = a[i + 1] - a[i], v = a[i + 2] - a[i + 1];
    return std::abs(std::atan2(glm::cross(u, v).z, glm::dot(u, v)));
  };
  EXPECT_GT(turn(480), 3.0 * turn(10));
}

TEST(Magnetic, SpaceFillingCurvesNeverCrossUnrelatedCurves) {
  SpaceFillParams P;
  P.size = glm::dvec3(300, 400, 0);
  P.max_curves = 60;
  P.child_spacing = 40;
  MagneticField f;
  f.noise = 1.0;  // the Perlin variant
  MagneticResult r = grow_magnetic(P, f, 3);
  ASSERT_GT(r.curves.size(), 20u);
  std::vector<int> used_pairs(P.pairs.size(), 0);
  for (size_t c = 0; c < r.curves.size(); ++c) {
    const MagneticCurve& curve = r.curves[c];
    ++used_pairs[size_t(curve.pair)];
    for (const auto& x : curve.points) {
      // In bounds, and in a cell owned by the curve itself or its parent.
      ASSERT_GE(x.x, 0.0);
      ASSERT_LE(x.x, P.size.x);
      ASSERT_GE(x.y, 0.0);
      ASSERT_LE(x.y, P.size.y);
      int32_t owner = r.owner[r.cell_of(x)];
      EXPECT_TRUE(owner == int32_t(c) || owner == curve.parent) << "curve " << c << " owner " << owner;
    }
    if (curve.parent >= 0) {
      const MagneticCurve& parent = r.curves[size_t(curve.parent)];
      ASSERT_LT(curve.parent_point, parent.points.size());
      EXPECT_EQ(curve.points[0], parent.points[curve.parent_point]);  // starts on the parent
    }
  }
  // The fallback to smaller spirals is exercised.
  EXPECT_GT(used_pairs[0], 0);
  EXPECT_GT(used_pairs[1] + used_pairs[2] + used_pairs[3], 0);
}

TEST(Magnetic, ReliefModelIsPlanarAndSvgHasEveryCurve) {
  TreeModel m = generate_from_species_text(default_species_text("magnetic"), "magnetic_klimt.toml");
  ASSERT_GT(m.branches.vertices.size(), 0u);
  float max_radius = 0.2f;  // trunk_radius 0.14 plus margin
  for (const Vertex& v : m.branches.vertices) EXPECT_LE(std::abs(v.position.z), max_radius);
  EXPECT_GE(double(m.meta["height"]), 4.0);
  std::string svg = magnetic_svg_from_species_text(default_species_text("magnetic"), "k.toml", std::nullopt);
  size_t lines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, size_t(m.meta["curves"]));
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
}

TEST(Magnetic, ThreeDVariantLeavesThePlane) {
  std::string text = read_text(species("magnetic_3d"));
  TreeModel m = generate_from_species_text(text, "magnetic_3d.toml");
  float zmax = 0.0f;
  for (const Vertex& v : m.branches.vertices) zmax = std::max(zmax, std::abs(v.position.z));
  EXPECT_GT(zmax, 1.0f);
}

TEST(Magnetic, DefaultPresetIsTheFileAndDeterministic) {
  EXPECT_EQ(default_species_text("magnetic"), read_text(species("magnetic_klimt")));
  auto bytes = [&](uint64_t seed) {
    return encode_glb(generate_from_species_text(default_species_text("magnetic"), "k.toml", {seed}));
  };
  EXPECT_EQ(bytes(4), bytes(4));
  EXPECT_NE(bytes(4), bytes(5));
}

TEST(Magnetic, PresetsFitTheBudget) {
  for (const char* name : {"magnetic_3d"}) {
    TreeModel m = generate_from_species(species(name));
    EXPECT_LE(m.branches.indices.size() / 3, 6500u) << name;
    EXPECT_LE(m.leaves.size(), 2500u) << name;
    EXPECT_GE(m.leaves.size(), 100u) << name;
  }
}

TEST(Magnetic, ErrorsNameTheKey) {
  auto expect_key = [&](const std::string& text, const std::string& key) {
    try {
      generate_from_species_text(text, "t.toml");
      ADD_FAILURE() << "no error for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_key("method = \"magnetic\"\ndt = 5.0\n", "dt");
  expect_key("method = \"magnetic\"\nmax_curves = 20000\n[[spiral]]\nT = 100000\nalpha = 0.8\n", "max_curves");
  expect_key("method = \"magnetic\"\n[[spiral]]\nT = 50\nalpha = 0.8\n[[spiral]]\nT = 650\nalpha = 0.8\n", "T");
  expect_key("method = \"magnetic\"\nfield_tilt = 1.0\n", "field_tilt");
  expect_key("method = \"magnetic\"\nprofile = \"sawtooth\"\n", "profile");
  expect_key("method = \"magnetic\"\ndomain = \"sphere\"\n", "domain");
}

TEST(Magnetic, TrunkClearDelaysTheTrunksFirstChild) {
  // The trunk (curve 0) releases no child before arc length trunk_clear; the other curves
  // keep child_spacing.
  auto first_release_arc = [](const MagneticResult& r) {
    double best = 1e30;
    for (const MagneticCurve& c : r.curves) {
      if (c.parent != 0) continue;
      const auto& pts = r.curves[0].points;
      double arc = 0.0;
      for (uint32_t k = 1; k <= c.parent_point && k < pts.size(); ++k) arc += glm::length(pts[k] - pts[k - 1]);
      best = std::min(best, arc);
    }
    return best;
  };
  SpaceFillParams P;
  P.size = glm::dvec3(300, 400, 0);
  P.max_curves = 40;
  P.child_spacing = 40;
  MagneticField f;
  MagneticResult plain = grow_magnetic(P, f, 3);
  P.trunk_clear = 150;
  MagneticResult clear = grow_magnetic(P, f, 3);
  EXPECT_LT(first_release_arc(plain), 100.0);
  EXPECT_GE(first_release_arc(clear), 150.0 - 1e-6);
  EXPECT_LT(first_release_arc(clear), 1e29);  // the trunk still has children
}

TEST(Magnetic, DomeEndsCurvesOnARoundedCrown) {
  // With domain = dome every point of every curve lies in the half ellipsoid, and the limbs
  // that a box would cut flat at its ceiling end lower toward the rim.
  SpaceFillParams P;
  P.size = glm::dvec3(400, 300, 400);
  P.max_curves = 60;
  P.child_spacing = 30;
  MagneticField f;
  f.three_d = true;
  f.tilt = 1.0;
  size_t outside_in_box = 0, points_in_box = 0;
  for (const MagneticCurve& c : grow_magnetic(P, f, 5).curves)
    for (const glm::dvec3& x : c.points) outside_in_box += !inside_dome(P, true, x), ++points_in_box;
  EXPECT_GT(outside_in_box, points_in_box / 50) << "the box's curves never leave the dome: the test shows nothing";
  P.domain = Domain::Dome;
  MagneticResult dome = grow_magnetic(P, f, 5);
  ASSERT_GT(dome.curves.size(), 20u);
  for (const MagneticCurve& c : dome.curves)
    for (const glm::dvec3& x : c.points) ASSERT_TRUE(inside_dome(P, true, x)) << x.x << " " << x.y << " " << x.z;
  // The dome itself: its top and floor centre are in, a top corner of the box is not.
  EXPECT_TRUE(inside_dome(P, true, {200, 300, 200}));
  EXPECT_TRUE(inside_dome(P, true, {200, 0, 200}));
  EXPECT_FALSE(inside_dome(P, true, {399, 299, 200}));
}
