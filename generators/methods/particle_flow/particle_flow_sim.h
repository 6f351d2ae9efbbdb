// Particle tracing (Neubert 2012 ch3.4, Algorithm 1): particles seeded in proportion to the voxel
// density flow down to the tree base, attracted by their nearest neighbour and steered by
// the direction field; particles closer than a threshold merge and move on together; the
// traces form one rooted branching graph.
// Dynamics (3.4): x'' = f/m as the first-order system [x, x'] = [x', f/m], integrated with
// explicit Euler, Heun or classical RK4 (3.5, 3.6). [ours] (the source leaves weights,
// threshold, masses and the merge rule open):
//   f = k (s u(x) - x'),  u = normalize(w_base b + w_field F(x) + w_neighbour n)
// with b the unit vector to the base, F the 3D direction field, n the unit vector to the
// nearest neighbour within attract_radius (frozen during a step), s the cruise speed; the
// drag term keeps speeds bounded. Mass m = mass * count^(1/4) (count = merged particles):
// thick streams are reluctant to turn. Merge: the lower-index particle survives at the
// count-weighted mean position and velocity. A particle within arrival_radius of the base
// joins the root. A particle within the merge radius of an earlier particle's trace joins
// that trace (see particle_flow_sim.cpp). After `iterations` steps any particle still moving
// is joined to the root by a straight trace (reported as forced_joins).
#pragma once
#include <cstdint>
#include <vector>

#include "generators/methods/particle_flow/particle_flow_density.h"
#include "generators/methods/particle_flow/particle_flow_field.h"
#include "generators/tree/tree_graph.h"

namespace forest {

// One explicit step y(t + h) of y' = f(t, y) (Neubert 2012 eq. 3.5 / Heun / eq. 3.6). State
// types need y + y, double * y.
template <class State, class F>
State euler_step(const State& y, double t, double h, F&& f) {
  return y + h * f(t, y);
}
template <class State, class F>
State heun_step(const State& y, double t, double h, F&& f) {
  State k1 = f(t, y);
  State k2 = f(t + h, y + h * k1);
  return y + (0.5 * h) * (k1 + k2);
}
template <class State, class F>
State rk4_step(const State& y, double t, double h, F&& f) {
  State k1 = f(t, y);
  State k2 = f(t + 0.5 * h, y + (0.5 * h) * k1);
  State k3 = f(t + 0.5 * h, y + (0.5 * h) * k2);
  State k4 = f(t + h, y + h * k3);
  return y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

// Position and velocity of one particle.
struct Phase {
  glm::dvec3 x{0.0};
  glm::dvec3 v{0.0};
};
inline Phase operator+(const Phase& a, const Phase& b) { return {a.x + b.x, a.v + b.v}; }
inline Phase operator*(double s, const Phase& a) { return {s * a.x, s * a.v}; }

// `count` positions drawn with probability proportional to alpha (a voxel by the cumulative
// distribution, then uniformly inside it). Empty grid -> empty result.
std::vector<glm::dvec3> seed_particles(const DensityGrid& grid, size_t count, uint64_t seed);

enum class Integrator { Euler, Heun, RK4 };

struct FlowParams {
  size_t particles = 1000;
  int iterations = 200;
  Integrator integrator = Integrator::RK4;
  double w_base = 0.35;
  double w_field = 1.0;
  double w_neighbour = 0.5;
  double stiffness = 1.0;          // k
  double mass = 2.0;
  double speed = 0.0;              // m per iteration; 0 = 1.6 * farthest seed distance / iterations
  double merge_radius = 0.0;       // m; 0 = 0.6 voxel
  double attract_radius = 0.0;     // m; 0 = 2 voxels
  double arrival_radius = 0.0;     // m; 0 = 2 * speed
  double segment_length = 0.0;     // m between trace nodes; 0 = 0.5 voxel
};

struct FlowResult {
  TreeGraph graph;                 // root (base) first, parent < own index
  std::vector<size_t> active;      // active particles before each iteration, then at the end
  size_t arrived = 0;              // particles that reached the base by themselves
  size_t forced_joins = 0;         // particles joined to the root after the last iteration
  size_t merges = 0;
  size_t trace_joins = 0;          // particles that joined an earlier particle's trace
  std::vector<glm::dvec3> seeds;   // initial positions (tips of the graph)
};

FlowResult trace_particles(const DensityGrid& grid, const DirectionField3D& field, glm::dvec3 base,
                           const FlowParams& params, uint64_t seed);

}  // namespace forest
