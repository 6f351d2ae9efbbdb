// Species keys of method "silhouettes" (all optional; ranges checked):
//   name, seed; drawing = .json / .svg file (relative to the species file; roles "axis" +
//   "silhouette" at level 0, optional level-1 "axis" over-sketches and "silhouette"
//   sub-silhouettes, optional "leaf"); without it the synthetic "round" drawing is used
//   (synthetic = "round" | "poplar"); bottom_angle / top_angle (BAF, degrees), levels,
//   fill_overlap, fill_samples, style_copy ("none", "sketched": the over-sketched first-level
//   branch's style onto its siblings, "richest": the style of the sibling with most children),
//   phyllotaxis ("none", "spiral", "decussate", "whorl3"),
//   density (extra 3D branches per inferred one), gibbs_iterations (<= 3000), max_branches,
//   tip_radius, pipe_exponent; plus the shared look keys (model/look_keys.h) and foliage keys
//   (tree/foliage.h).
#include "generators/methods/silhouettes/silhouettes_method.h"

#include <algorithm>
#include <cmath>

#include "generators/core/rng.h"
#include "generators/methods/silhouettes/silhouettes_placement.h"
#include "generators/methods/silhouettes/silhouettes_style.h"
#include "generators/methods/sketch_mrf/sketch_propagation.h"
#include "generators/tree/leaves.h"
#include "generators/tree/pipe_model.h"

namespace forest {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<glm::dvec2> resample(const std::vector<glm::dvec2>& c, int n) {
  Polyline2 line(c);
  std::vector<glm::dvec2> out;
  for (int k = 0; k <= n; ++k) out.push_back(line.at(double(k) / n));
  return out;
}

Polygon2 open_polygon(std::vector<glm::dvec2> pts) {
  if (pts.size() > 3 && glm::length(pts.front() - pts.back()) < 1e-9) pts.pop_back();
  return pts;
}

double cross2(glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; }

// Star-shaped union of an ellipse and discs centred on it, sampled around its centre.
Polygon2 bumpy_crown(glm::dvec2 centre, glm::dvec2 radii, const std::vector<std::pair<glm::dvec2, double>>& discs) {
  Polygon2 out;
  for (int k = 0; k < 180; ++k) {
    double a = 2.0 * kPi * k / 180.0;
    glm::dvec2 d(std::cos(a), std::sin(a));
    double r = 1.0 / std::sqrt(d.x * d.x / (radii.x * radii.x) + d.y * d.y / (radii.y * radii.y));
    for (auto [c, rho] : discs) {
      glm::dvec2 q = c - centre;
      double b = glm::dot(d, q), disc = b * b - glm::dot(q, q) + rho * rho;
      if (disc >= 0) r = std::max(r, b + std::sqrt(disc));
    }
    out.push_back(centre + r * d);
  }
  return out;
}

std::vector<std::pair<glm::dvec2, double>> discs_on(glm::dvec2 centre, glm::dvec2 radii,
                                                    const std::vector<double>& degrees,
                                                    const std::vector<double>& rho) {
  std::vector<std::pair<glm::dvec2, double>> out;
  for (size_t i = 0; i < degrees.size(); ++i) {
    double a = degrees[i] * kPi / 180.0;
    out.push_back({centre + glm::dvec2(radii.x * std::cos(a), radii.y * std::sin(a)), rho[i]});
  }
  return out;
}

Stroke make_stroke(const std::string& id, const std::string& role, int level, std::vector<glm::dvec2> pts) {
  Stroke s;
  s.id = id;
  s.role = role;
  s.level = level;
  s.points = std::move(pts);
  return s;
}

Polygon2 ellipse(glm::dvec2 c, double rx, double ry, int n) {
  Polygon2 p;
  for (int k = 0; k <= n; ++k) p.emplace_back(c.x + rx * std::cos(2 * kPi * k / n), c.y + ry * std::sin(2 * kPi * k / n));
  return p;
}

}  // namespace

std::vector<std::pair<glm::dvec2, double>> silhouettes_round_discs() {
  return discs_on({0, 6}, {3, 2.5}, {20, 60, 90, 120, 160}, {1.1, 1.3, 1.2, 1.0, 1.15});
}

Drawing silhouettes_synthetic_drawing(const std::string& name) {
  Drawing d;
  d.file = "synthetic:" + name;
  if (name == "round") {
    Polygon2 crown = bumpy_crown({0, 6}, {3, 2.5}, silhouettes_round_discs());
    crown.push_back(crown.front());
    d.strokes.push_back(make_stroke("trunk", "axis", 0, {{0, 0}, {0, 8}}));
    d.strokes.push_back(make_stroke("crown", "silhouette", 0, crown));
    // Scripted refinement: the branch into the 20-degree bump redrawn with a lift.
    d.strokes.push_back(make_stroke("redrawn", "axis", 1, {{0, 4.6}, {0.9, 5.3}, {1.7, 5.9}, {2.4, 6.4}, {2.95, 6.9}}));
    d.strokes.push_back(make_stroke("leaf", "leaf", 0, ellipse({0, 0}, 0.15, 0.05, 16)));
  } else {
    Polygon2 crown = bumpy_crown({0, 8.5}, {1.8, 6.0},
                                 discs_on({0, 8.5}, {1.8, 6.0}, {-30, 15, 55, 90, 125, 165, 210},
                                          {0.8, 0.9, 0.8, 0.9, 0.8, 0.9, 0.8}));
    crown.push_back(crown.front());
    d.strokes.push_back(make_stroke("trunk", "axis", 0, {{0, 0}, {0.05, 7}, {0, 14}}));
    d.strokes.push_back(make_stroke("crown", "silhouette", 0, crown));
    d.strokes.push_back(make_stroke("leaf", "leaf", 0, ellipse({0, 0}, 0.1, 0.04, 16)));
  }
  return d;
}

std::vector<SilhouetteNode> infer_hierarchy(const Drawing& drawing, const SilhouetteParams& params) {
  const Stroke* trunk = nullptr;
  const Stroke* crown = nullptr;
  std::vector<const Stroke*> redrawn, redrawn_crowns;
  for (size_t i = 0; i < drawing.strokes.size(); ++i) {
    const Stroke& s = drawing.strokes[i];
    if (s.role == "leaf") continue;
    if (s.role != "axis" && s.role != "silhouette")
      stroke_error(drawing, i, "role", "silhouettes reads roles \"axis\", \"silhouette\" and \"leaf\", not \"" + s.role + "\"");
    if (s.level > 1) stroke_error(drawing, i, "level", "only levels 0 (trunk, crown) and 1 (over-sketches) are read");
    const Stroke** slot = s.role == "axis" ? &trunk : &crown;
    if (s.level == 0) {
      if (*slot) stroke_error(drawing, i, "role", "a second level-0 " + s.role);
      *slot = &s;
    } else {
      (s.role == "axis" ? redrawn : redrawn_crowns).push_back(&s);
    }
    if (s.role == "silhouette" && s.points.size() < 3) stroke_error(drawing, i, "points", "a silhouette needs >= 3 points");
  }
  if (!trunk) throw InputError(drawing.file, 0, "strokes", "no level-0 \"axis\" stroke (the trunk)");
  if (!crown) throw InputError(drawing.file, 0, "strokes", "no level-0 \"silhouette\" stroke (the crown)");
  Polygon2 sil = open_polygon(crown->points);
  if (polygon_area(sil) < 1e-6) throw InputError(drawing.file, crown->line, "silhouette", "the crown silhouette encloses no area");

  std::vector<SilhouetteNode> h(1);
  h[0].branch.curve = resample(trunk->points, 32);
  h[0].branch.crown = sil;
  const BranchingAngleFunction baf0 = BranchingAngleFunction::linear(params.bottom_angle, params.top_angle);
  const double tree_size = std::max(Polyline2(h[0].branch.curve).length(), 1e-6);

  // Depth-first: infer the children of node k inside its silhouette, then recurse.
  std::vector<int> stack{0};
  for (size_t guard = 0; !stack.empty() && guard < 100000; ++guard) {
    int k = stack.back();
    stack.pop_back();
    const int level = h[size_t(k)].level;
    if (level >= params.levels || h.size() >= params.max_branches) continue;
    Polyline2 axis(h[size_t(k)].branch.curve);
    Polygon2 psil = h[size_t(k)].branch.crown;
    if (psil.size() < 3 || axis.length() < 0.03 * tree_size) continue;
    BranchingAngleFunction baf = baf0;
    // Branches start where the axis is inside the silhouette (the trunk below the crown
    // and the first 15 % of a branch stay bare [ours]).
    double t_lo = 0.15;
    if (k == 0) {
      t_lo = 1.0;
      for (int s = 0; s <= 64; ++s)
        if (point_in_polygon(psil, axis.at(s / 64.0))) { t_lo = s / 64.0; break; }
      if (t_lo >= 1.0) t_lo = 0.5;
    }
    std::vector<Branch2D> branches;
    std::vector<Bump> bumps = silhouette_bumps(psil);
    if (bumps.empty()) {  // a smooth crown: one branch toward its far end, the fill-in does the rest
      glm::dvec2 far = psil[0];
      for (glm::dvec2 p : psil)
        if (glm::length(p - axis.at(0.0)) > glm::length(far - axis.at(0.0))) far = p;
      glm::dvec2 out = glm::normalize(far - axis.at(0.0));
      double r = 0.25 * glm::length(far - axis.at(0.0));
      bumps.push_back({far - r * out, out, r});
    }
    for (const Bump& b : bumps) {
      if (glm::length(b.end - axis.at(0.0)) < 0.3 * axis.length()) continue;  // the base corner
      Branch2D br = infer_branch(axis, b, baf, t_lo);
      if (br.curve.size() < 2) continue;
      branches.push_back(std::move(br));
    }
    if (k == 0 && !redrawn.empty() && !branches.empty()) {
      // Step D: an over-sketch replaces the nearest branch, adds a BAF sample, and reshapes
      // the other (inferred) siblings by span transfer after re-inferring their bases.
      for (const Stroke* s : redrawn) {
        double t = axis.closest_t(s->points.front());
        glm::dvec2 base = axis.at(t);
        size_t best = 0;
        double best_cost = 1e300;
        for (size_t i = 0; i < branches.size(); ++i) {
          if (branches[i].sketched) continue;
          double c = glm::length(branches[i].curve.front() - base) + glm::length(branches[i].curve.back() - s->points.back());
          if (c < best_cost) best_cost = c, best = i;
        }
        std::vector<glm::dvec2> curve = s->points;
        curve.front() = base;
        glm::dvec2 start = curve[1] - curve[0], tangent = axis.tangent(t);
        double angle = std::acos(std::clamp(glm::dot(glm::normalize(start), tangent), -1.0, 1.0)) * 180.0 / kPi;
        baf.add_sample(t, angle);
        Branch2D& b = branches[best];
        b.curve = resample(curve, 16);
        b.t = t;
        b.side = cross2(tangent, s->points.back() - base) > 0 ? -1 : 1;
        b.sketched = true;
      }
      const Branch2D* source = nullptr;
      for (const Branch2D& b : branches)
        if (b.sketched) source = &b;
      std::vector<glm::dvec2> src = source->curve;
      int src_side = source->side;
      for (Branch2D& b : branches) {
        if (b.sketched) continue;
        Bump bump{b.curve.back(), glm::normalize(b.curve.back() - b.curve[b.curve.size() - 2]), b.end_radius};
        Branch2D again = infer_branch(axis, bump, baf, t_lo);
        if (again.curve.size() < 2) continue;
        std::vector<glm::dvec2> shaped = src;
        if (again.side != src_side) {  // a sibling on the other side gets the mirrored shape
          glm::dvec2 a = glm::normalize(src.back() - src.front());
          for (glm::dvec2& p : shaped) {
            glm::dvec2 d = p - src.front();
            p = src.front() + 2.0 * glm::dot(d, a) * a - d;
          }
        }
        again.curve = span_transfer(shaped, again.curve.front(), again.curve.back());
        b = std::move(again);
      }
    }
    for (Branch2D& b : branches) b.crown = infer_sub_silhouette(psil, b.curve.front(), b.curve.back(), b.end_radius);
    if (k == 0)
      for (const Stroke* s : redrawn_crowns) {  // a redrawn sub-silhouette replaces the inferred one
        Polygon2 c = open_polygon(s->points);
        size_t best = 0, most = 0;
        for (size_t i = 0; i < branches.size(); ++i) {
          size_t inside = 0;
          for (glm::dvec2 p : branches[i].curve) inside += point_in_polygon(c, p);
          if (inside > most) most = inside, best = i;
        }
        if (most > 0) branches[best].crown = c;
      }
    std::vector<Branch2D> more = fill_in(axis, psil, branches, baf, t_lo, params.fill_samples, params.max_overlap);
    branches.insert(branches.end(), more.begin(), more.end());
    for (Branch2D& b : branches) {
      if (h.size() >= params.max_branches) break;
      SilhouetteNode n;
      n.branch = std::move(b);
      n.parent = k;
      n.level = level + 1;
      h[size_t(k)].children.push_back(int(h.size()));
      stack.push_back(int(h.size()));
      h.push_back(std::move(n));
    }
  }
  return h;
}

namespace {

struct Embedding {
  glm::dvec3 origin{0.0};
  glm::dvec2 base{0.0};
  glm::dvec3 ex{1, 0, 0}, ey{0, 1, 0};
  glm::dvec3 map(glm::dvec2 p) const { return origin + (p.x - base.x) * ex + (p.y - base.y) * ey; }
  glm::dvec3 linear(glm::dvec2 v) const { return v.x * ex + v.y * ey; }
};

// The method's own species keys; the registry adds the common and the look keys.
constexpr std::string_view kKeys[] = {
    "drawing", "synthetic", "bottom_angle", "top_angle", "levels", "fill_overlap", "fill_samples",
    "style_copy", "phyllotaxis", "density", "gibbs_iterations", "max_branches", "tip_radius",
    "pipe_exponent"};

Skeleton skeleton_pass(const TomlTable& t, uint64_t seed) {
  Drawing drawing;
  if (t.has("drawing")) {
    drawing = read_drawing(t.existing_file("drawing"));
  } else {
    drawing = silhouettes_synthetic_drawing(t.choice("synthetic", "round", {"round", "poplar"}));
  }
  SilhouetteParams sp;
  sp.bottom_angle = t.number("bottom_angle", 80.0, 0.0, 180.0);
  sp.top_angle = t.number("top_angle", 30.0, 0.0, 180.0);
  sp.levels = int(t.integer("levels", 3, 1, 5));
  sp.max_overlap = t.number("fill_overlap", 0.2, 0.0, 1.0);
  sp.fill_samples = int(t.integer("fill_samples", 8, 0, 64));
  sp.max_branches = size_t(t.integer("max_branches", 4000, 1, 50000));
  BranchPhyllotaxis phyllo;
  std::string pname = t.choice("phyllotaxis", "spiral", {"none", "spiral", "decussate", "whorl3"});
  phyllotaxis_preset(pname, phyllo);
  double density = t.number("density", 0.6, 0.0, 4.0);
  GibbsParams gp;
  gp.max_iterations = int(t.integer("gibbs_iterations", 3000, 0, 3000));

  std::string style = t.choice("style_copy", "none", {"none", "sketched", "richest"});

  std::vector<SilhouetteNode> h = infer_hierarchy(drawing, sp);
  size_t restyled = 0;
  if (style != "none") {  // step G: the source's style onto every other first-level branch
    int source = -1;
    for (int c : h[0].children)
      if (style == "sketched" ? h[size_t(c)].branch.sketched
                              : source < 0 || h[size_t(c)].children.size() > h[size_t(source)].children.size())
        source = c;
    if (source < 0) t.fail("style_copy", "the drawing has no over-sketched first-level branch to copy the style of");
    Rng style_rng(seed, /*stream=*/43);
    restyled = copy_style(h, source, style_rng, sp.max_branches * 2);
  }
  const size_t inferred_count = h.size();

  // 3D: every node gets an embedding of its drawing plane; children are turned about
  // their parent's axis by the azimuths of the Gibbs process.
  std::vector<Embedding> emb(h.size());
  emb[0].base = h[0].branch.curve.front();
  emb[0].origin = glm::dvec3(emb[0].base, 0.0);
  CrownSurface surface{h[0].branch.crown, h[0].branch.curve.front().x};
  Rng rng(seed, /*stream=*/41);
  std::vector<int> order{0};
  for (size_t q = 0; q < order.size(); ++q) {
    int k = order[q];
    Polyline2 axis(h[size_t(k)].branch.curve);
    double L = std::max(axis.length(), 1e-9);
    std::vector<int> kids = h[size_t(k)].children;
    // Extra branches fill the 3D space the drawing cannot show (5.3); copies of the
    // nearest inferred sibling, placed anywhere on the parent.
    int extra = int(std::lround(density * double(kids.size())));
    std::vector<InsertionPoint> pts;
    double u_lo = L;
    for (int c : kids) {
      const Branch2D& b = h[size_t(c)].branch;
      InsertionPoint p;
      p.u = p.u_min = p.u_max = b.t * L;
      double ref = b.side > 0 ? 0.0 : 180.0;
      p.theta = ref, p.theta_min = ref - 45.0, p.theta_max = ref + 45.0;
      pts.push_back(p);
      u_lo = std::min(u_lo, p.u);
    }
    for (int e = 0; e < extra && h.size() + 1 < sp.max_branches * 2; ++e) {
      InsertionPoint p;
      p.u_min = u_lo, p.u_max = L;
      p.u = p.u_min + (p.u_max - p.u_min) * rng.uniform();
      p.theta = 360.0 * rng.uniform();
      pts.push_back(p);
    }
    place_insertion_points(pts, L, phyllo, gp, hash64(seed, uint64_t(k)));
    for (size_t e = kids.size(); e < pts.size(); ++e) {
      int src = kids[0];
      for (int c : kids)
        if (std::abs(h[size_t(c)].branch.t * L - pts[e].u) < std::abs(h[size_t(src)].branch.t * L - pts[e].u)) src = c;
      double t = pts[e].u / L;
      const glm::dvec2 from = h[size_t(src)].branch.curve.front(), base = axis.at(t);
      auto move = [&](glm::dvec2 p) { return base + (p - from); };
      int id = copy_subtree(h, src, k, t, move, sp.max_branches * 2);
      if (id < 0) break;
      // The copy keeps its source's side; its azimuth is the free theta of the Gibbs process.
      kids.push_back(id);
    }
    emb.resize(h.size());
    for (size_t i = 0; i < kids.size(); ++i) {
      int c = kids[i];
      Branch2D& b = h[size_t(c)].branch;
      glm::dvec2 t2 = axis.tangent(b.t), n2 = glm::dvec2(t2.y, -t2.x) * double(b.side);
      glm::dvec3 t3 = glm::normalize(emb[size_t(k)].linear(t2));
      glm::dvec3 n3 = glm::normalize(emb[size_t(k)].linear(glm::dvec2(t2.y, -t2.x)));
      glm::dvec3 b3 = glm::cross(t3, n3);
      double th = pts[i].theta * kPi / 180.0;
      glm::dvec3 r3 = std::cos(th) * n3 + std::sin(th) * b3;
      Embedding e;
      e.base = b.curve.front();
      e.origin = emb[size_t(k)].map(axis.at(b.t));
      e.ex = t2.x * t3 + n2.x * r3;
      e.ey = t2.y * t3 + n2.y * r3;
      // Extra first-level branches reach the crown's surface of revolution (5.6).
      if (k == 0 && size_t(c) >= inferred_count) {
        auto tip = [&](double s) { return e.origin + s * (e.map(b.curve.back()) - e.origin); };
        double lo = 0.3, hi = 1.6;
        if (!surface.contains(tip(lo))) hi = lo;
        for (int it = 0; it < 30 && hi > lo; ++it) {
          double m = 0.5 * (lo + hi);
          (surface.contains(tip(m)) ? lo : hi) = m;
        }
        e.ex *= lo, e.ey *= lo;
      }
      emb[size_t(c)] = e;
      order.push_back(c);
    }
  }

  // Graph: the trunk's points, then every branch chained from its parent's nearest node.
  TreeGraph graph;
  std::vector<std::vector<int>> nodes_of(h.size());
  glm::dvec3 root = emb[0].map(h[0].branch.curve.front());
  for (int k : order) {
    const SilhouetteNode& n = h[size_t(k)];
    std::vector<glm::dvec3> pts3;
    // Finer levels are short: every 4th point of their curve is enough for the mesh.
    const size_t step = n.level >= 2 ? 4 : 1;
    for (size_t i = 0; i < n.branch.curve.size(); ++i)
      if (i % step == 0 || i + 1 == n.branch.curve.size()) pts3.push_back(emb[size_t(k)].map(n.branch.curve[i]) - root);
    int attach = -1;
    if (n.parent >= 0) {
      double best = 1e300;
      for (int id : nodes_of[size_t(n.parent)]) {
        double d = glm::length(glm::dvec3(graph.nodes[size_t(id)].position) - pts3[0]);
        if (d < best) best = d, attach = id;
      }
    }
    int prev = attach;
    for (size_t i = (attach >= 0 ? 1 : 0); i < pts3.size(); ++i) {
      TreeNode tn;
      tn.position = glm::vec3(pts3[i]);
      tn.parent = prev;
      tn.order = uint32_t(n.level);
      graph.nodes.push_back(tn);
      prev = int(graph.nodes.size()) - 1;
      nodes_of[size_t(k)].push_back(prev);
    }
    if (attach >= 0) nodes_of[size_t(k)].insert(nodes_of[size_t(k)].begin(), attach);
  }
  assign_pipe_radii(graph, float(t.number("tip_radius", 0.008, 1e-5, 1.0)), float(t.number("pipe_exponent", 2.3, 1.0, 4.0)));

  Skeleton out{std::move(graph)};
  out.meta["silhouettes"] = {{"inferred_branches", inferred_count - 1}, {"branches_3d", h.size() - 1},
                               {"first_level", h[0].children.size()}, {"restyled", restyled}};
  return out;
}

const char* builtin_preset() {
  return R"toml(method = "silhouettes"
# Built-in preset: the reference note's synthetic drawing (trunk, bumpy round crown, one
# over-sketched branch, leaf silhouette), made in memory.
name = "silhouettes"
seed = 1
synthetic = "round"
phyllotaxis = "spiral"
levels = 3
# foliage: a method demo: the shared foliage model, blade 6-10 cm on shoots of 25-35 cm.
leaf_shape = "ovate"
foliage = "shoots"
leaf_size = 0.08
leaf_size_jitter = 0.2
leaf_phyllotaxis = "alternate"
leaves_per_shoot = 6
shoot_length = 0.3
shoot_spacing = 0.1
foliage_depth = 2.0
shoot_angle = 50
leaf_angle = 55
shoots_per_tip = 3
shoots_per_spray = 3
leaf_color_jitter = 0.1
autumn_color = [0.55, 0.34, 0.05]
bark_color = [0.24, 0.18, 0.12]
leaf_color = [0.15, 0.33, 0.07]
)toml";
}

// Writes dir/round.json, dir/round.svg and dir/poplar.json.
void write_inputs(const std::filesystem::path& dir) {
  Drawing round = silhouettes_synthetic_drawing("round");
  Drawing poplar = silhouettes_synthetic_drawing("poplar");
  write_drawing_files(dir, {{"round.json", drawing_to_json(round)},
                            {"round.svg", drawing_to_svg(round)},
                            {"poplar.json", drawing_to_json(poplar)}});
}

}  // namespace

constinit const MethodEntry kSilhouettesMethod{"silhouettes", kKeys, skeleton_pass, builtin_preset,
                                               write_inputs};

}  // namespace forest
