#include "generators/methods/lsystem/lsystem.h"

#include <array>
#include <cmath>
#include <cstdlib>

#include "generators/core/input_error.h"
#include "generators/core/rng.h"
#include "generators/tree/leaves.h"

namespace forest {

namespace {

constexpr float kDegToRad = 3.14159265358979323846f / 180.0f;

bool takes_argument(char c) {
  switch (c) {
    case 'F': case 'f': case '+': case '-': case '&': case '^': case '\\': case '/': case '!':
      return true;
    default:
      return false;
  }
}

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

bool is_argument_char(char c) {
  return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+';
}

// Parses "(number)" at s[i] (s[i] == '('); returns the index after ')' or npos on error.
size_t parse_argument(std::string_view s, size_t i, double* value) {
  size_t close = s.find(')', i + 1);
  if (close == std::string_view::npos || close == i + 1) return std::string_view::npos;
  std::string text(s.substr(i + 1, close - i - 1));
  for (char c : text)
    if (!is_argument_char(c)) return std::string_view::npos;
  char* end = nullptr;
  double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::string_view::npos;
  *value = v;
  return close + 1;
}

// Rotates the pair (a, b) in their plane: a toward b by `angle` radians.
void rotate_pair(glm::vec3& a, glm::vec3& b, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  glm::vec3 a2 = a * c + b * s;
  glm::vec3 b2 = b * c - a * s;
  a = a2;
  b = b2;
}

// Rodrigues rotation of v about the unit axis k.
glm::vec3 rotate_about(glm::vec3 v, glm::vec3 k, float angle) {
  float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0f - c);
}

struct Turtle {
  glm::vec3 pos{0.0f};
  glm::vec3 heading{0.0f, 1.0f, 0.0f};  // H
  glm::vec3 left{-1.0f, 0.0f, 0.0f};    // L; H x L = U
  glm::vec3 up{0.0f, 0.0f, 1.0f};       // U
  int32_t node = 0;
  float step = 1.0f;
  uint32_t depth = 0;

  // Keeps the frame orthonormal against rounding drift over thousands of turns.
  void orthonormalize() {
    heading = glm::normalize(heading);
    left = glm::normalize(left - glm::dot(left, heading) * heading);
    up = glm::cross(heading, left);
  }
};

}  // namespace

std::optional<std::string> check_lsystem_syntax(std::string_view s) {
  long depth = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    char c = s[i];
    if (c == '[') ++depth;
    if (c == ']' && --depth < 0)
      return "unbalanced brackets: ']' at position " + std::to_string(i) + " closes nothing";
    if (c == '(') {
      if (i == 0 || !takes_argument(s[i - 1]))
        return "'(' at position " + std::to_string(i) +
               " must follow one of F f + - & ^ \\ / ! (an argument)";
      double v;
      size_t next = parse_argument(s, i, &v);
      if (next == std::string_view::npos)
        return "bad argument at position " + std::to_string(i) + ": expected (number)";
      i = next - 1;
      continue;
    }
    if (c == ')') return "')' at position " + std::to_string(i) + " without '('";
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126)
      return "non-printable or non-ASCII symbol at position " + std::to_string(i);
  }
  if (depth != 0) return "unbalanced brackets: " + std::to_string(depth) + " '[' never closed";
  return std::nullopt;
}

std::string rewrite(const LSystem& system, int iterations, uint64_t seed, size_t max_symbols) {
  if (iterations < 0) throw InputError("iterations must be >= 0");
  // Productions per predecessor letter, with cumulative weights for the stochastic choice.
  struct Choices {
    std::vector<const Production*> rules;
    std::vector<double> cumulative;
  };
  std::array<Choices, 256> table;
  for (const Production& p : system.productions) {
    if (!is_letter(p.predecessor))
      throw InputError(std::string("predecessor '") + p.predecessor + "' must be a letter");
    if (!(p.weight > 0.0) || !std::isfinite(p.weight))
      throw InputError("production weights must be finite and > 0");
    Choices& c = table[static_cast<unsigned char>(p.predecessor)];
    c.rules.push_back(&p);
    c.cumulative.push_back((c.cumulative.empty() ? 0.0 : c.cumulative.back()) + p.weight);
  }

  Rng rng(seed, /*stream=*/1);
  std::string current = system.axiom;
  if (current.size() > max_symbols)
    throw InputError("axiom is longer than " + std::to_string(max_symbols) + " symbols");
  std::string next;
  for (int it = 0; it < iterations; ++it) {
    next.clear();
    for (size_t i = 0; i < current.size(); ++i) {
      char c = current[i];
      if (c == '(') {  // arguments are copied verbatim, never rewritten
        size_t close = current.find(')', i);
        if (close == std::string::npos) close = current.size() - 1;
        next.append(current, i, close - i + 1);
        i = close;
        continue;
      }
      const Choices& ch = table[static_cast<unsigned char>(c)];
      if (ch.rules.empty()) {
        next.push_back(c);
      } else {
        size_t pick = 0;
        if (ch.rules.size() > 1) {  // deterministic systems draw nothing
          double u = rng.uniform() * ch.cumulative.back();
          while (pick + 1 < ch.rules.size() && u >= ch.cumulative[pick]) ++pick;
        }
        next += ch.rules[pick]->successor;
      }
      if (next.size() > max_symbols)
        throw InputError("the string exceeds " + std::to_string(max_symbols) +
                         " symbols at iteration " + std::to_string(it + 1) + " of " +
                         std::to_string(iterations) + "; lower iterations");
    }
    current.swap(next);
  }
  return current;
}

TreeGraph interpret(std::string_view symbols, const TurtleParams& params, uint64_t seed) {
  if (auto err = check_lsystem_syntax(symbols)) throw InputError(*err);
  Rng rng(seed, /*stream=*/2);
  TreeGraph graph;
  graph.nodes.push_back(TreeNode{});  // the root, at the origin

  Turtle t;
  t.step = params.step;
  std::vector<Turtle> stack;
  glm::vec3 tropism = glm::length(params.tropism) > 0.0f ? glm::normalize(params.tropism)
                                                         : glm::vec3(0.0f);

  auto turn_angle = [&](double arg_deg) {
    double a = arg_deg;
    if (params.angle_jitter_deg > 0.0f) a += params.angle_jitter_deg * rng.symmetric();
    return float(a) * kDegToRad;
  };
  auto move = [&](double factor) {
    double len = double(t.step) * factor;
    if (params.step_jitter > 0.0f) len *= 1.0 + double(params.step_jitter) * rng.symmetric();
    t.pos += t.heading * float(len);
    // Tropism (ABOP 2.4): bend the heading toward T by strength * |H x T| after each move.
    if (params.tropism_strength != 0.0f) {
      glm::vec3 axis = glm::cross(t.heading, tropism);
      float s = glm::length(axis);
      if (s > 1e-6f) {
        axis /= s;
        float a = params.tropism_strength * s;
        t.heading = rotate_about(t.heading, axis, a);
        t.left = rotate_about(t.left, axis, a);
      }
    }
    t.orthonormalize();
  };

  for (size_t i = 0; i < symbols.size(); ++i) {
    char c = symbols[i];
    double arg = 0.0;
    bool has_arg = false;
    if (takes_argument(c) && i + 1 < symbols.size() && symbols[i + 1] == '(') {
      size_t next = parse_argument(symbols, i + 1, &arg);  // validated above
      has_arg = true;
      i = next - 1;
    }
    const double angle_arg = has_arg ? arg : double(params.angle_deg);
    switch (c) {
      case 'F': {
        move(has_arg ? arg : 1.0);
        TreeNode n;
        n.position = t.pos;
        n.parent = t.node;
        n.order = t.depth;
        t.node = int32_t(graph.nodes.size());
        graph.nodes.push_back(n);
        break;
      }
      case 'f': move(has_arg ? arg : 1.0); break;
      case '+': rotate_pair(t.heading, t.left, turn_angle(angle_arg)); t.orthonormalize(); break;
      case '-': rotate_pair(t.heading, t.left, -turn_angle(angle_arg)); t.orthonormalize(); break;
      case '&': rotate_pair(t.heading, t.up, -turn_angle(angle_arg)); t.orthonormalize(); break;
      case '^': rotate_pair(t.heading, t.up, turn_angle(angle_arg)); t.orthonormalize(); break;
      case '\\': rotate_pair(t.left, t.up, turn_angle(angle_arg)); t.orthonormalize(); break;
      case '/': rotate_pair(t.left, t.up, -turn_angle(angle_arg)); t.orthonormalize(); break;
      case '|': t.heading = -t.heading; t.left = -t.left; break;
      case '!': t.step *= float(has_arg ? arg : double(params.length_scale)); break;
      case '[':
        stack.push_back(t);
        ++t.depth;
        if (params.roll_jitter_deg > 0.0f) {
          rotate_pair(t.left, t.up, float(params.roll_jitter_deg * rng.symmetric()) * kDegToRad);
          t.orthonormalize();
        }
        break;
      case ']':
        t = stack.back();  // balanced: checked above
        stack.pop_back();
        break;
      case 'L': {
        float azimuth = float(rng.uniform(0.0, 6.283185307179586));
        float size = params.leaf_size;
        if (params.leaf_size_jitter > 0.0f)
          size *= float(1.0 + double(params.leaf_size_jitter) * rng.symmetric());
        LeafPlacement leaf = orient_leaf(t.pos, t.heading, azimuth, params.leaf_angle_deg * kDegToRad,
                                         glm::vec3(0.0f, 1.0f, 0.0f), size);
        leaf.color = leaf_color_variation(rng, params.leaf_color_jitter);
        graph.leaves.push_back(leaf);
        break;
      }
      default: break;  // other letters only steer the rewriting
    }
  }
  return graph;
}

}  // namespace forest
