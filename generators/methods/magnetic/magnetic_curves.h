// Magnetic curves (Xu 2015 ch7, Xu & Mould): a charged particle in a magnetic field feels
// F = q v × B; with q varying in time its path has continuously varying curvature (radius
// r = m v / (q B)). Branching releases child particles along a parent curve with random
// charge sign; space filling tries spiral sizes (T, α) from large to small and rejects a
// curve that enters an occupancy-grid cell owned by any curve but itself or its parent.
// 2D as in the thesis (xy plane, B along z); [ours] a 3D variant with a 3D field.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

enum class ChargeProfile {
  Constant,  // q0
  Power,     // q0 (t + 1)^(−α): radius grows (Fig. 7.1 row 1; +1 avoids t = 0)
  Spiral,    // q0 (T − t)^(−α), t ∈ [0, T): radius shrinks to a spiral (space filling)
  Triangle,  // mean + triangle wave of `amplitude`, `period`
  Square,    // mean + square wave of `amplitude`, `period`
};

struct Charge {
  ChargeProfile profile = ChargeProfile::Spiral;
  double q0 = 1.0;
  double alpha = 0.7;
  double T = 650.0;       // curve duration (time units); Spiral's singular end
  double amplitude = 1.0, mean = 0.5, period = 100.0;
  double sign = 1.0;      // ±1: winding direction
};
double charge_at(const Charge& c, double t);

struct MagneticField {
  double b0 = 1.0;
  double noise = 0.0;          // 0: constant; 1: B_z = b0·0.5(1 + noise(x/s, y/s)) (ch7.2.4)
  double noise_scale = 50.0;   // s
  uint64_t seed = 0;
  bool three_d = false;        // [ours] B = b0·normalize(n1, tilt, n2), n1, n2 smooth noise
  double tilt = 0.3;
};
glm::dvec3 field_at(const MagneticField& f, glm::dvec3 p);

// Smooth lattice value noise in [−1, 1] (a stand-in for the thesis' Perlin noise).
double value_noise(double x, double y, double z, uint64_t seed);

struct Particle {
  glm::dvec3 position{0.0};
  glm::dvec3 velocity{0.0, 1.0, 0.0};
  double mass = 1.0;
};
// Forward Euler: v += (q/m)(v × B) dt, renormalized to the old speed [ours: keeps |v| exact],
// then p += v dt.
void lorentz_step(Particle& p, double q, glm::dvec3 B, double dt);

// Free flight (no occupancy, no bounds) for `steps` steps; returns every position.
std::vector<glm::dvec3> trace_particle(Particle p, const Charge& c, const MagneticField& f,
                                       double dt, int steps);

struct MagneticCurve {
  std::vector<glm::dvec3> points;
  int32_t parent = -1;        // index of the parent curve
  uint32_t parent_point = 0;  // points[0] == parent's points[parent_point]
  uint32_t depth = 0;
  int pair = 0;               // which (T, α) pair succeeded
};

struct SpiralPair {
  double T = 650.0, alpha = 0.8;
};

// [ours] The domain's shape. A box ends every limb that reaches its top at one height: a
// flat-topped crown. A dome, the half ellipsoid standing on the box's floor and touching its
// walls and ceiling, ends limbs on a rounded surface: lower toward the crown's rim.
enum class Domain { Box, Dome };

struct SpaceFillParams {
  glm::dvec3 size{600.0, 800.0, 600.0};  // domain [0, size]; z ignored in 2D
  Domain domain = Domain::Box;
  double cell = 4.0;                     // occupancy grid cell
  double dt = 0.5, speed = 1.0, mass = 1.0;
  Charge charge;                         // profile, q0 and waves; T and α come from pairs
  double trunk_q0 = 1.0;                 // q0 of the first particle (a straighter trunk when small)
  std::vector<SpiralPair> pairs{{650, 0.8}, {450, 0.75}, {250, 0.7}, {50, 0.65}};
  double child_spacing = 60.0;           // arc length between releases on a parent
  // [ours] Arc length of the first curve (the trunk) before its first release: a clear bole
  // (a broadleaf's trunk up to its first limbs). < 0: child_spacing, as on every curve.
  double trunk_clear = -1.0;
  int max_curves = 300;
  int max_depth = 6;
};

struct MagneticResult {
  std::vector<MagneticCurve> curves;
  std::vector<int32_t> owner;  // occupancy grid: curve id per cell, −1 empty
  int dims[3] = {1, 1, 1};
  double cell = 1.0;
  size_t cell_of(glm::dvec3 p) const;
};

// First particle at the bottom centre heading up; children BFS over curves. Deterministic.
MagneticResult grow_magnetic(const SpaceFillParams& params, const MagneticField& field, uint64_t seed);
// Whether p lies in the dome of `params` (Domain::Dome; z ignored in 2D), surface included.
bool inside_dome(const SpaceFillParams& params, bool three_d, glm::dvec3 p);

// SVG of the curves projected on xy (y up in the model, down in SVG); stroke width shrinks
// with depth.
std::string magnetic_svg(const MagneticResult& result, glm::dvec2 size);
void write_magnetic_svg(const MagneticResult& result, glm::dvec2 size, const std::filesystem::path& out);

}  // namespace forest
