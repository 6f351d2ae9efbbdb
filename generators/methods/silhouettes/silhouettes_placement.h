// Method `silhouettes` (Wither 2009), part 3: 3D placement of the branches around their parent
// (step H). Insertion points p = (theta, u) on the unfolded parent cylinder; a Gibbs-like
// process minimizes F = sum_{i != j} g(i, j) by depletion-replacement (Ripley 1979): move
// one random point to a random position in its domain, keep the move only if F drops.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace forest {

struct BranchPhyllotaxis {
  int whorl = 0;        // n organs per node; 0 = no pattern term (g = f)
  double phi_deg = 0;   // angle between successive nodes
};
// "none", "spiral" (n 1, 144 deg), "decussate" (n 2, 90 deg), "whorl3" (n 3, 60 deg);
// false for an unknown name.
bool phyllotaxis_preset(const std::string& name, BranchPhyllotaxis& out);

struct InsertionPoint {
  double u = 0.0, theta = 0.0;        // arc length on the parent (m), azimuth (degrees)
  double u_min = 0.0, u_max = 0.0;    // domain D_i
  double theta_min = 0.0, theta_max = 360.0;  // degrees; theta_max - theta_min >= 360 = free
};

struct GibbsParams {
  double alpha = 20.0;      // f = 1 / (1 + alpha d)
  double w_close = 2.0;     // g = w_close f + w_pattern d_pattern
  double w_pattern = 1.0;
  int max_iterations = 3000;
};

// d(i, j) = |(du/L, dtheta/360)|^2 with theta cyclic.
double insertion_distance(const InsertionPoint& a, const InsertionPoint& b, double length);
// Distance to the nearest privileged position of the phyllotactic pattern, in [0, 0.5]:
// l = L n / N, d_node = floor(|du| / l), d_ang = (dtheta - d_node phi) mod gamma,
// d_pattern = min(d_ang, gamma - d_ang) / gamma with gamma = 360 / n (reconstructed ⚠).
double pattern_distance(const InsertionPoint& a, const InsertionPoint& b, double length, int count,
                        const BranchPhyllotaxis& p);
double gibbs_energy(const std::vector<InsertionPoint>& points, double length, const BranchPhyllotaxis& p,
                    const GibbsParams& params);

struct GibbsResult {
  std::vector<double> energy;  // F after every iteration (first entry: the start)
  int iterations = 0;
};
// Optimizes `points` in place (each stays in its domain). Deterministic for a seed.
GibbsResult place_insertion_points(std::vector<InsertionPoint>& points, double length, const BranchPhyllotaxis& p,
                                   const GibbsParams& params, uint64_t seed);

}  // namespace forest
