#include "generators/methods/plantons/plantons_organs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "generators/core/input_error.h"
#include "generators/tree/leaves.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 safe_normalize(glm::dvec3 v, glm::dvec3 fallback) {
  double len = glm::length(v);
  return len > 1e-12 ? v / len : fallback;
}

}  // namespace

const char* organ_type_name(OrganType type) { return type == OrganType::Stem ? "stem" : "leaf"; }

int organ_param_count(OrganType type) { return type == OrganType::Stem ? kStemParams : kLeafParams; }

OrganFrame organ_frame(glm::dvec3 d) {
  OrganFrame f;
  f.y = safe_normalize(d, glm::dvec3(0, 1, 0));
  glm::dvec3 up(0, 1, 0);
  glm::dvec3 x = up - glm::dot(up, f.y) * f.y;
  if (glm::length(x) < 1e-6) {
    glm::dvec3 wx(1, 0, 0);
    x = wx - glm::dot(wx, f.y) * f.y;
  }
  f.x = glm::normalize(x);
  f.z = glm::cross(f.x, f.y);
  return f;
}

glm::dvec3 direction_from_angles(glm::dvec3 tangent, double theta, double phi) {
  OrganFrame f = organ_frame(tangent);
  return std::cos(theta) * f.y + std::sin(theta) * (std::cos(phi) * f.x + std::sin(phi) * f.z);
}

void angles_of_direction(glm::dvec3 tangent, glm::dvec3 d, double& theta, double& phi) {
  OrganFrame f = organ_frame(tangent);
  d = safe_normalize(d, f.y);
  theta = std::acos(std::clamp(glm::dot(d, f.y), -1.0, 1.0));
  double x = glm::dot(d, f.x), z = glm::dot(d, f.z);
  phi = (std::abs(x) + std::abs(z) > 1e-12) ? std::atan2(z, x) : 0.0;
  if (phi <= -kPi) phi = kPi;
}

std::array<glm::dvec3, 4> stem_control_points(const Organ& stem) {
  OrganFrame f = organ_frame(glm::dvec3(stem.direction));
  const double L = stem.s[0];
  auto world = [&](double x, double y, double z) { return L * (x * f.x + y * f.y + z * f.z); };
  glm::dvec3 p0(stem.base);
  return {p0, p0 + world(stem.s[3], stem.s[4], stem.s[5]), p0 + world(stem.s[6], stem.s[7], stem.s[8]),
          p0 + L * f.y};
}

glm::dvec3 bezier_point(const std::array<glm::dvec3, 4>& p, double u) {
  double v = 1.0 - u;
  return v * v * v * p[0] + 3.0 * v * v * u * p[1] + 3.0 * v * u * u * p[2] + u * u * u * p[3];
}

glm::dvec3 bezier_tangent(const std::array<glm::dvec3, 4>& p, double u) {
  double v = 1.0 - u;
  glm::dvec3 d = 3.0 * v * v * (p[1] - p[0]) + 6.0 * v * u * (p[2] - p[1]) + 3.0 * u * u * (p[3] - p[2]);
  return safe_normalize(d, safe_normalize(p[3] - p[0], glm::dvec3(0, 1, 0)));
}

std::array<glm::dvec3, 4> fit_bezier(const std::vector<glm::dvec3>& pts, std::vector<double>& u) {
  const size_t n = pts.size();
  u.assign(n, 0.0);
  double total = 0.0;
  for (size_t i = 1; i < n; ++i) u[i] = total += glm::length(pts[i] - pts[i - 1]);
  for (size_t i = 1; i < n; ++i) u[i] = total > 0.0 ? u[i] / total : double(i) / double(n - 1);
  glm::dvec3 p0 = pts.front(), p3 = pts.back();
  std::array<glm::dvec3, 4> c{p0, p0 + (p3 - p0) / 3.0, p0 + 2.0 * (p3 - p0) / 3.0, p3};
  if (n < 4) return c;
  // Normal equations of min Σ |B(u_i) − x_i|² over P1, P2 (2×2, shared by x, y, z).
  double a11 = 0, a12 = 0, a22 = 0;
  glm::dvec3 r1(0.0), r2(0.0);
  for (size_t i = 0; i < n; ++i) {
    double t = u[i], v = 1.0 - t;
    double b0 = v * v * v, b1 = 3 * v * v * t, b2 = 3 * v * t * t, b3 = t * t * t;
    glm::dvec3 rhs = pts[i] - b0 * p0 - b3 * p3;
    a11 += b1 * b1;
    a12 += b1 * b2;
    a22 += b2 * b2;
    r1 += b1 * rhs;
    r2 += b2 * rhs;
  }
  double det = a11 * a22 - a12 * a12;
  if (std::abs(det) < 1e-12) return c;
  c[1] = (a22 * r1 - a12 * r2) / det;
  c[2] = (a11 * r2 - a12 * r1) / det;
  return c;
}

double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

void azimuths_to_divergences(OrganTree& tree) {
  std::vector<std::vector<size_t>> kids(tree.organs.size());
  for (size_t k = 1; k < tree.organs.size(); ++k)
    if (tree.organs[k].parent >= 0) kids[size_t(tree.organs[k].parent)].push_back(k);
  for (auto& list : kids) {
    std::stable_sort(list.begin(), list.end(), [&](size_t a, size_t b) { return tree.organs[a].t < tree.organs[b].t; });
    double prev = 0.0;
    for (size_t k : list) {
      double abs_phi = tree.organs[k].phi;
      tree.organs[k].phi = wrap_angle(abs_phi - prev);
      prev = abs_phi;
    }
  }
}

namespace {

struct Axis {
  std::vector<uint32_t> nodes;  // nodes[0] is the attachment (or the root node)
  int32_t parent = -1;          // parent axis
  size_t parent_slot = 0;       // index of nodes[0] in the parent axis
};

glm::dvec3 node_pos(const TreeGraph& g, uint32_t i) { return glm::dvec3(g.nodes[i].position); }

}  // namespace

OrganTree organs_from_graph(const TreeGraph& graph) {
  const size_t n = graph.nodes.size();
  auto children = children_of(graph);
  if (n < 2 || children[0].empty()) throw InputError("plantons: a sample tree has no branch");

  // Axes, breadth-first. owner[v] = (axis, slot) of the axis that v belongs to as an own node
  // (every node but the root belongs to exactly one axis; the root to axis 0).
  std::vector<Axis> axes;
  std::vector<std::pair<int32_t, size_t>> owner(n, {-1, 0});
  auto start_axis = [&](uint32_t from, uint32_t first, int32_t parent, size_t slot) {
    Axis a;
    a.nodes = {from, first};
    a.parent = parent;
    a.parent_slot = slot;
    axes.push_back(std::move(a));
  };
  // The root axis starts at node 0 and continues like any other.
  {
    Axis a;
    a.nodes = {0};
    axes.push_back(a);
    owner[0] = {0, 0};
  }
  // Continuation child of node v arriving along `incoming`.
  auto continuation = [&](uint32_t v, glm::dvec3 incoming) -> int64_t {
    int64_t best = -1;
    double best_dot = -2.0;
    for (uint32_t c : children[v]) {
      if (graph.nodes[c].order != graph.nodes[v].order && v != 0) continue;
      double d = glm::dot(safe_normalize(node_pos(graph, c) - node_pos(graph, v), glm::dvec3(0, 1, 0)), incoming);
      if (d > best_dot) {
        best_dot = d;
        best = c;
      }
    }
    return best;
  };
  auto walk = [&](size_t ai) {
    Axis& a = axes[ai];
    glm::dvec3 incoming(0, 1, 0);
    if (a.nodes.size() >= 2)
      incoming = safe_normalize(node_pos(graph, a.nodes[1]) - node_pos(graph, a.nodes[0]), incoming);
    for (size_t k = a.nodes.size() - 1; k < a.nodes.size(); ++k) {  // grows while walking
      uint32_t v = a.nodes[k];
      owner[v] = {int32_t(ai), k};
      if (k > 0) incoming = safe_normalize(node_pos(graph, v) - node_pos(graph, a.nodes[k - 1]), incoming);
      int64_t next = continuation(v, incoming);
      if (next >= 0) a.nodes.push_back(uint32_t(next));
    }
  };
  walk(0);
  for (size_t ai = 0; ai < axes.size(); ++ai) {
    if (ai > 0) walk(ai);
    // Side children of this axis's nodes, in node order: new axes (breadth-first overall).
    std::vector<uint32_t> own = axes[ai].nodes;
    for (size_t k = 0; k < own.size(); ++k) {
      uint32_t v = own[k];
      if (owner[v].first != int32_t(ai)) continue;  // the attachment node belongs to the parent
      uint32_t cont = k + 1 < own.size() ? own[k + 1] : UINT32_MAX;
      for (uint32_t c : children[v])
        if (c != cont) start_axis(v, c, int32_t(ai), k);
    }
  }

  // Stems: Bézier fit, parameters, attachment.
  OrganTree tree;
  tree.organs.resize(axes.size());
  std::vector<std::vector<double>> axis_u(axes.size());
  std::vector<std::array<glm::dvec3, 4>> curves(axes.size());
  for (size_t ai = 0; ai < axes.size(); ++ai) {
    const Axis& a = axes[ai];
    std::vector<glm::dvec3> pts;
    for (uint32_t v : a.nodes) pts.push_back(node_pos(graph, v));
    if (pts.size() < 2) pts.push_back(pts[0] + glm::dvec3(0, 1e-3, 0));  // a root without continuation
    std::array<glm::dvec3, 4> c = fit_bezier(pts, axis_u[ai]);
    curves[ai] = c;
    Organ& o = tree.organs[ai];
    o.type = OrganType::Stem;
    o.parent = a.parent;
    o.base = glm::vec3(c[0]);
    glm::dvec3 chord = c[3] - c[0];
    double L = std::max(glm::length(chord), 1e-6);
    o.direction = glm::vec3(safe_normalize(chord, glm::dvec3(0, 1, 0)));
    OrganFrame f = organ_frame(glm::dvec3(o.direction));
    glm::dvec3 q1 = (c[1] - c[0]) / L, q2 = (c[2] - c[0]) / L;
    // Base radius: node 0 of a side axis is its parent's; extrapolate the first two own nodes
    // back to u = 0 (at most doubling) instead.
    double r_base = graph.nodes[a.nodes[0]].radius;
    if (a.parent >= 0) {
      const std::vector<double>& u = axis_u[ai];
      double r1 = graph.nodes[a.nodes[1]].radius;
      r_base = r1;
      if (a.nodes.size() > 2 && u[2] > u[1]) {
        double r2 = graph.nodes[a.nodes[2]].radius;
        r_base = std::clamp(r1 + (r1 - r2) * u[1] / (u[2] - u[1]), r1, 2.0 * r1);
      }
    }
    float r_tip = graph.nodes[a.nodes.back()].radius;
    o.s = {L, r_base, r_tip, glm::dot(q1, f.x), glm::dot(q1, f.y), glm::dot(q1, f.z),
           glm::dot(q2, f.x), glm::dot(q2, f.y), glm::dot(q2, f.z)};
  }
  for (size_t ai = 1; ai < axes.size(); ++ai) {
    Organ& o = tree.organs[ai];
    const size_t p = size_t(axes[ai].parent);
    o.t = axis_u[p][axes[ai].parent_slot];
    angles_of_direction(bezier_tangent(curves[p], o.t), glm::dvec3(o.direction), o.theta, o.phi);
  }
  angles_of_direction(glm::dvec3(0, 1, 0), glm::dvec3(tree.organs[0].direction), tree.organs[0].theta,
                      tree.organs[0].phi);

  // Leaves: on the axis of the nearest node.
  for (const LeafPlacement& leaf : graph.leaves) {
    glm::vec3 p = leaf.position;
    size_t best = 0;
    float best_d = std::numeric_limits<float>::max();
    for (size_t v = 0; v < n; ++v) {
      glm::vec3 d = graph.nodes[v].position - p;
      float d2 = glm::dot(d, d);
      if (d2 < best_d) {
        best_d = d2;
        best = v;
      }
    }
    auto [ai, slot] = owner[best];
    if (ai < 0) continue;  // unreachable node (not under the root)
    Organ o;
    o.type = OrganType::Leaf;
    o.parent = ai;
    o.t = axis_u[size_t(ai)][slot];
    o.base = p;
    o.direction = glm::vec3(safe_normalize(glm::dvec3(leaf.rotation * glm::vec3(0, 1, 0)), glm::dvec3(0, 1, 0)));
    angles_of_direction(bezier_tangent(curves[size_t(ai)], o.t), glm::dvec3(o.direction), o.theta, o.phi);
    o.s = {double(leaf.scale)};
    tree.organs.push_back(std::move(o));
  }
  azimuths_to_divergences(tree);
  return tree;
}

TreeGraph graph_from_organs(const OrganTree& tree, const OrganMeshing& meshing) {
  TreeGraph g;
  const size_t m = tree.organs.size();
  if (m == 0) return g;
  std::vector<std::vector<uint32_t>> kids(m);
  for (size_t i = 1; i < m; ++i)
    if (tree.organs[i].parent >= 0) kids[size_t(tree.organs[i].parent)].push_back(uint32_t(i));
  std::vector<int32_t> attach(m, -1);  // graph node each organ starts at
  {
    TreeNode root;
    root.position = tree.organs[0].base;
    root.radius = std::max(float(tree.organs[0].s[1]), meshing.min_radius);
    g.nodes.push_back(root);
    attach[0] = 0;
  }
  std::vector<uint32_t> depth(m, 0);
  glm::dvec3 leaf_sum(0.0);
  double leaf_min_y = 1e30, leaf_max_y = -1e30;
  size_t leaf_count = 0;
  for (size_t i = 0; i < m; ++i) {
    const Organ& o = tree.organs[i];
    if (o.parent >= 0) depth[i] = depth[size_t(o.parent)] + 1;
    if (o.type == OrganType::Leaf) {
      leaf_sum += glm::dvec3(o.base);
      leaf_min_y = std::min(leaf_min_y, double(o.base.y));
      leaf_max_y = std::max(leaf_max_y, double(o.base.y));
      ++leaf_count;
      continue;
    }
    if (attach[i] < 0) continue;  // a stem under a leaf: not produced by our code
    // Node parameters: evenly spaced plus one per stem child.
    std::vector<double> us;
    for (int k = 1; k <= meshing.segments; ++k) us.push_back(double(k) / meshing.segments);
    for (uint32_t c : kids[i])
      if (tree.organs[c].type == OrganType::Stem && tree.organs[c].t > 1e-4) us.push_back(tree.organs[c].t);
    std::sort(us.begin(), us.end());
    std::vector<double> uniq;
    for (double u : us)
      if (uniq.empty() || u - uniq.back() > 1e-4) uniq.push_back(u);
    auto c = stem_control_points(o);
    std::vector<std::pair<double, int32_t>> nodes_at{{0.0, attach[i]}};
    int32_t prev = attach[i];
    for (double u : uniq) {
      TreeNode node;
      node.position = glm::vec3(bezier_point(c, u));
      node.radius = std::max(float(o.s[1] + (o.s[2] - o.s[1]) * u), meshing.min_radius);
      node.parent = prev;
      node.order = depth[i];
      prev = int32_t(g.nodes.size());
      g.nodes.push_back(node);
      nodes_at.push_back({u, prev});
    }
    for (uint32_t ch : kids[i]) {
      if (tree.organs[ch].type != OrganType::Stem) continue;
      double t = tree.organs[ch].t;
      size_t best = 0;
      for (size_t k = 1; k < nodes_at.size(); ++k)
        if (std::abs(nodes_at[k].first - t) < std::abs(nodes_at[best].first - t)) best = k;
      attach[ch] = nodes_at[best].second;
    }
  }
  if (leaf_count > 0) {
    glm::dvec3 inside = leaf_sum / double(leaf_count);
    inside.y -= 0.25 * (leaf_max_y - leaf_min_y);
    for (const Organ& o : tree.organs) {
      if (o.type != OrganType::Leaf) continue;
      LeafFrame f = leaf_frame(o.base, o.direction, glm::vec3(inside));
      LeafPlacement l;
      l.position = o.base;
      l.rotation = leaf_rotation(f);
      l.scale = float(o.s[0]);
      g.leaves.push_back(l);
    }
  }
  return g;
}

}  // namespace forest
