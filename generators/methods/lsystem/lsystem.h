// Bracketed, stochastic, 3D L-systems (Prusinkiewicz & Lindenmayer, "The Algorithmic Beauty of
// Plants"; Neubert 2012 ch2): string rewriting, then a turtle that turns the string into a
// TreeGraph skeleton. Radii and leaves are separate passes (pipe_model.h, leaves.h).
//
// Alphabet of the turtle (everything else is carried through rewriting and ignored when drawn):
//   F      move forward one step and create a node (consecutive F make a chain of nodes)
//   f      move forward without a node (the next node connects across the gap)
//   + -    yaw left / right by the angle        & ^   pitch down / up
//   \ /    roll left / right                    |     turn around (yaw 180 degrees)
//   [ ]    push / pop the turtle: a branch; nodes made inside have order = bracket depth
//   !      multiply the step length by length_scale (thinner, shorter twigs further out)
//   L      place a leaf at the turtle (only when the preset uses L at all)
// Any of F f + - & ^ \ / ! may be followed by an explicit argument in parentheses, e.g. +(72)
// or F(0.5): an angle in degrees for the turns, a factor of the step for F/f/!. Arguments
// are written by the author in successors; they are never rewritten (predecessors are
// letters only).
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "generators/core/limits.h"

#include <glm/glm.hpp>

#include "generators/tree/tree_graph.h"

namespace forest {

struct Production {
  char predecessor = 'F';  // an ASCII letter
  std::string successor;
  double weight = 1.0;  // alternatives for one predecessor are chosen with these weights
};

struct LSystem {
  std::string axiom;
  std::vector<Production> productions;
};

// Strings larger than this are refused: n iterations of growth is exponential, and a typo in
// `iterations` should be an error message, not an exhausted machine.

// Describes what is wrong with the brackets or arguments of `s`, or nullopt when fine.
std::optional<std::string> check_lsystem_syntax(std::string_view s);

// Applies the productions `iterations` times in parallel to every symbol. Stochastic choices
// come from a deterministic RNG seeded by `seed`. Throws InputError (no file, plain message)
// when the string would exceed `max_symbols` or a predecessor is not a letter.
std::string rewrite(const LSystem& system, int iterations, uint64_t seed,
                    size_t max_symbols = kMaxLSystemSymbols);

struct TurtleParams {
  float angle_deg = 22.5f;         // default turn angle
  float angle_jitter_deg = 0.0f;   // each turn: angle + jitter * U(-1, 1)
  float roll_jitter_deg = 0.0f;    // each '[': random roll about the heading (3D plants)
  float step = 1.0f;               // meters per F
  float step_jitter = 0.0f;        // each F: step * (1 + jitter * U(-1, 1)), jitter < 1
  float length_scale = 0.9f;       // factor applied to the step by '!'
  glm::vec3 tropism{0.0f, -1.0f, 0.0f};  // direction branches bend toward (gravity: -Y)
  float tropism_strength = 0.0f;   // bend per F: angle = strength * |H x T| (ABOP eq. 2.x)
  // Leaves placed by L: blade tilted away from the heading by leaf_angle, length leaf_size.
  float leaf_angle_deg = 40.0f;
  float leaf_size = 0.1f;
  float leaf_size_jitter = 0.0f;
  float leaf_color_jitter = 0.0f;  // per-leaf color variation (leaves.h leaf_color_variation)
};

// Interprets `symbols` with a 3D turtle starting at the origin heading +Y. Node 0 is the
// root; every F appends a node whose parent is the turtle's current node. Radii are left 0.
// Leaves from L symbols go to graph.leaves. Randomness (jitter) from `seed`.
// Unbalanced brackets or bad arguments -> InputError.
TreeGraph interpret(std::string_view symbols, const TurtleParams& params, uint64_t seed);

}  // namespace forest
