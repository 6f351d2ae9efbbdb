#include "generators/methods/sketch_mrf/sketch_templates.h"

#include <algorithm>
#include <cmath>

#include "generators/core/hull_2d.h"
#include "generators/methods/lsystem/lsystem.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct TemplateRecipe {
  const char* name;
  const char* axiom;
  std::vector<Production> productions;
  int iterations;
  TurtleParams turtle;
  uint64_t seed;
  float leaf_size;
  int leaves_per_tip;
};

TurtleParams turtle(float angle, float step, float length_scale, float tropism, float roll) {
  TurtleParams p;
  p.angle_deg = angle;
  p.angle_jitter_deg = 4.0f;
  p.roll_jitter_deg = roll;
  p.step = step;
  p.step_jitter = 0.1f;
  p.length_scale = length_scale;
  p.tropism_strength = tropism;
  return p;
}

// After scenes/species/broadleaf.toml, conifer.toml and fig2_1.toml (fewer iterations: the
// statistics settle long before the leaves do), plus a wide umbrella crown.
std::vector<TemplateRecipe> recipes() {
  return {
      {"broadleaf", "F(1.6)/(45)F(1.0)![&FA]/(94.74)[&FA]/(132.63)[&FA]",
       {{'A', "![&FA]/(94.74)[&FA]/(132.63)[&FA]", 0.3}, {'A', "!/(137.5)[&FA][^(10)FA]", 0.7}},
       4, turtle(30.0f, 1.6f, 0.78f, 0.14f, 25.0f), 11, 0.32f, 5},
      {"conifer", "F(1.8)A",
       {{'A', "F/(37)[&(78)B]/(90)[&(78)B]/(90)[&(78)B]/(90)[&(78)B]!A", 1.0},
        {'B', "F(0.42)[+C]/(180)B", 1.0}, {'C', "F(0.35)C", 0.5}, {'C', "C", 0.5}},
       8, turtle(50.0f, 1.0f, 0.95f, 0.10f, 10.0f), 5, 0.45f, 3},
      {"fig2_1", "X", {{'X', "F[[X]-X]F[+FX]-X", 1.0}, {'F', "FF", 1.0}},
       4, turtle(22.5f, 0.4f, 0.9f, 0.0f, 180.0f), 1, 0.15f, 2},
      {"umbrella", "F(3.0)A", {{'A', "!/(90)[&(55)FA][^(55)FA]", 1.0}},
       5, turtle(55.0f, 1.4f, 0.8f, 0.0f, 20.0f), 7, 0.3f, 4},
  };
}

glm::dvec3 rotate_view(glm::dvec3 p, int view) {
  double a = 2.0 * kPi * double(view) / double(kTemplateViews);
  return {p.x * std::cos(a) + p.z * std::sin(a), p.y, -p.x * std::sin(a) + p.z * std::cos(a)};
}

SketchTree as_sketch_tree(const SketchTemplate& t, int view, std::vector<double>& z) {
  SketchTree s;
  z.clear();
  s.parent = t.parent;
  s.children.assign(t.nodes.size(), {});
  glm::dvec2 lo(1e300), hi(-1e300);
  for (size_t i = 0; i < t.nodes.size(); ++i) {
    glm::dvec3 p = rotate_view(t.nodes[i], view);
    s.xy.emplace_back(p.x, p.y);
    z.push_back(p.z);
    lo = glm::min(lo, s.xy.back()), hi = glm::max(hi, s.xy.back());
    if (i > 0) s.children[size_t(t.parent[i])].push_back(int(i));
  }
  s.height = std::max({hi.x - lo.x, hi.y - lo.y, 1e-6});
  s.true_z = z;
  return s;
}


SketchTemplate build(const TemplateRecipe& r) {
  LSystem system{r.axiom, r.productions};
  TreeGraph g = interpret(rewrite(system, r.iterations, r.seed), r.turtle, r.seed);
  auto children = children_of(g);
  SketchTemplate t;
  t.name = r.name;
  t.leaf_size = r.leaf_size;
  t.leaves_per_tip = r.leaves_per_tip;
  // Keep the root, the branch points and the tips; chains between them become segments.
  std::vector<int> kept_index(g.nodes.size(), -1), nearest_kept(g.nodes.size(), -1);
  for (size_t i = 0; i < g.nodes.size(); ++i) {
    int p = g.nodes[i].parent;
    int up = p < 0 ? -1 : (kept_index[size_t(p)] >= 0 ? kept_index[size_t(p)] : nearest_kept[size_t(p)]);
    nearest_kept[i] = up;
    if (i == 0 || children[i].size() != 1) {
      kept_index[i] = int(t.nodes.size());
      t.nodes.push_back(glm::dvec3(g.nodes[i].position));
      t.parent.push_back(up);
    }
  }
  std::vector<double> z;
  SketchTree s = as_sketch_tree(t, 0, z);
  SketchDepths d{z, natural_labels(s, z)};
  t.omega = m_step(s, d, Omega{});
  for (int v = 0; v < kTemplateViews; ++v) {
    SketchTree sv = as_sketch_tree(t, v, z);
    TemplateView view;
    view.footprint = footprint_descriptor(std::vector<glm::dvec2>(sv.xy.begin() + 1, sv.xy.end()));
    view.stats = branch_stats_2d(sv.xy, sv.parent);
    t.views.push_back(view);
  }
  return t;
}

double score(const std::vector<double>& fs, const BranchStats2D& ss, bool crown, const TemplateView& e) {
  double lb = 0.0;
  for (int k = 0; k < 3; ++k)
    lb -= (ss.mu[k] - e.stats.mu[k]) * (ss.mu[k] - e.stats.mu[k]) /
          (ss.sd[k] * ss.sd[k] + e.stats.sd[k] * e.stats.sd[k] + 1e-12);
  if (!crown) return lb;
  double lc = 0.0;
  for (size_t k = 0; k < fs.size(); ++k) lc += (fs[k] - e.footprint[k]) * (fs[k] - e.footprint[k]);
  return lb - std::sqrt(lc);
}

}  // namespace

const std::vector<SketchTemplate>& sketch_template_database() {
  static const std::vector<SketchTemplate> db = [] {
    std::vector<SketchTemplate> out;
    for (const TemplateRecipe& r : recipes()) out.push_back(build(r));
    return out;
  }();
  return db;
}

int find_sketch_template(const std::string& name) {
  const auto& db = sketch_template_database();
  for (size_t i = 0; i < db.size(); ++i)
    if (db[i].name == name) return int(i);
  return -1;
}

std::vector<double> footprint_descriptor(const std::vector<glm::dvec2>& points) {
  std::vector<double> f(kFootprintDirections, 0.0);
  std::vector<glm::dvec2> hull = convex_hull_2d(points);
  if (hull.size() < 3) return f;
  glm::dvec2 lo(1e300), hi(-1e300);
  for (glm::dvec2 p : hull) lo = glm::min(lo, p), hi = glm::max(hi, p);
  double scale = 1.0 / std::max({hi.x - lo.x, hi.y - lo.y, 1e-12});
  glm::dvec2 c = 0.5 * (lo + hi);
  for (int k = 0; k < kFootprintDirections; ++k) {
    double a = 2.0 * kPi * k / kFootprintDirections;
    glm::dvec2 d(std::cos(a), std::sin(a));
    for (size_t i = 0; i < hull.size(); ++i) {
      glm::dvec2 p = hull[i] - c, q = hull[(i + 1) % hull.size()] - c, e = q - p;
      double den = d.x * e.y - d.y * e.x;
      if (std::abs(den) < 1e-15) continue;
      double t = (p.x * e.y - p.y * e.x) / den, u = (p.x * d.y - p.y * d.x) / den;
      if (u >= -1e-9 && u <= 1 + 1e-9 && t > 0) f[size_t(k)] = std::max(f[size_t(k)], t * scale);
    }
  }
  return f;
}

BranchStats2D branch_stats_2d(const std::vector<glm::dvec2>& xy, const std::vector<int>& parent) {
  std::vector<std::vector<int>> children(xy.size());
  for (size_t i = 1; i < xy.size(); ++i)
    if (parent[i] >= 0) children[size_t(parent[i])].push_back(int(i));
  std::vector<double> samples[3];
  for (size_t p = 1; p < xy.size(); ++p) {
    if (parent[p] < 0 || children[p].empty()) continue;
    glm::dvec2 vp = xy[p] - xy[size_t(parent[p])];
    if (glm::length(vp) < 1e-9) continue;
    std::vector<std::pair<double, double>> sa;  // (angle, s)
    for (int c : children[p]) {
      glm::dvec2 vc = xy[size_t(c)] - xy[p];
      if (glm::length(vc) < 1e-9) continue;
      double ang = std::acos(std::clamp(glm::dot(vc, vp) / (glm::length(vc) * glm::length(vp)), -1.0, 1.0));
      sa.emplace_back(ang, glm::length(vc) / glm::length(vp));
    }
    std::sort(sa.begin(), sa.end());
    for (size_t k = 0; k < sa.size(); ++k) {
      samples[0].push_back(sa[k].second);
      samples[k == 0 ? 1 : 2].push_back(sa[k].first);
    }
  }
  BranchStats2D st;
  for (int k = 0; k < 3; ++k) {
    if (samples[k].empty()) continue;
    double mu = 0.0, var = 0.0;
    for (double v : samples[k]) mu += v;
    mu /= double(samples[k].size());
    for (double v : samples[k]) var += (v - mu) * (v - mu);
    st.mu[k] = mu;
    st.sd[k] = std::max(std::sqrt(var / double(samples[k].size())), 1e-3);
  }
  return st;
}

TemplateChoice choose_template(const SketchTree& sketch) {
  std::vector<glm::dvec2> pts(sketch.xy.begin() + 1, sketch.xy.end());
  bool crown = !sketch.crown.empty();
  pts.insert(pts.end(), sketch.crown.begin(), sketch.crown.end());
  std::vector<double> fs = footprint_descriptor(pts);
  BranchStats2D ss = branch_stats_2d(sketch.xy, sketch.parent);
  TemplateChoice choice;
  const auto& db = sketch_template_database();
  for (size_t i = 0; i < db.size(); ++i) {
    double best = -1e300;
    for (int v = 0; v < kTemplateViews; ++v) {
      double l = score(fs, ss, crown, db[i].views[size_t(v)]);
      best = std::max(best, l);
      if (l > choice.score) choice.score = l, choice.index = int(i), choice.view = v;
    }
    choice.best_per_template.push_back(best);
  }
  return choice;
}

Drawing project_template(const SketchTemplate& t, int view, int generations, bool with_crown) {
  std::vector<double> z;
  SketchTree s = as_sketch_tree(t, view, z);
  std::vector<int> label = natural_labels(s, z);
  // Strokes follow apical children; each lateral child starts a stroke of its own.
  Drawing out;
  out.file = std::string("template:") + t.name;
  struct Start { int from; int child; int parent_stroke; int generation; };
  std::vector<Start> starts{{-1, 0, -1, 0}};
  for (size_t q = 0; q < starts.size(); ++q) {
    Start sp = starts[q];
    Stroke st;
    st.id = "s" + std::to_string(out.strokes.size());
    st.role = "branch";
    st.level = sp.generation;
    if (sp.parent_stroke >= 0) st.parent = out.strokes[size_t(sp.parent_stroke)].id;
    if (sp.from >= 0) {
      st.points.push_back(s.xy[size_t(sp.from)]);
      st.depth.push_back(z[size_t(sp.from)]);
    }
    int n = sp.child;
    int self = int(out.strokes.size());
    while (n >= 0) {
      st.points.push_back(s.xy[size_t(n)]);
      st.depth.push_back(z[size_t(n)]);
      int apical = -1;
      for (int c : s.children[size_t(n)])
        if (label[size_t(c)] == 0 || (n == 0 && apical < 0)) apical = c;
      for (int c : s.children[size_t(n)])
        if (c != apical && sp.generation + 1 < generations) starts.push_back({n, c, self, sp.generation + 1});
      n = apical;
    }
    out.strokes.push_back(std::move(st));
  }
  if (with_crown) {
    std::vector<glm::dvec2> hull = convex_hull_2d(std::vector<glm::dvec2>(s.xy.begin() + 1, s.xy.end()));
    Stroke crown;
    crown.id = "crown";
    crown.role = "crown";
    crown.points = hull;
    if (!hull.empty()) crown.points.push_back(hull.front());
    out.strokes.push_back(std::move(crown));
  }
  return out;
}

}  // namespace forest
