#include "generators/methods/plantons/plantons_samples.h"
#include "generators/core/limits.h"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/text_file.h"
#include "generators/species/registry.h"
#include "generators/methods/plantons/plantons_synth.h"

namespace forest {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct GtStem {
  double length, length_sd, r_base, r_tip, bend;  // bend: upward offset of P1, P2 (× L)
  double children, children_sd;
};

Planton gt_stem(const GtStem& g) {
  Planton x;
  x.type = OrganType::Stem;
  x.mean = {g.length, g.r_base, g.r_tip, 0.5 * g.bend, 1.0 / 3.0, 0.0, g.bend, 2.0 / 3.0, 0.0};
  std::vector<double> sd = {g.length_sd, 0.08 * g.r_base, 0.08 * g.r_tip, 0.01, 0.01, 0.01, 0.01, 0.01, 0.01};
  x.covariance.assign(size_t(kStemParams * kStemParams), 0.0);
  for (size_t k = 0; k < sd.size(); ++k) x.covariance[k * kStemParams + k] = sd[k] * sd[k];
  x.child_mean = g.children;
  x.child_sd = g.children_sd;
  return x;
}

void gt_transition(PlantonModel& m, size_t from, size_t to, double p, double t, double t_sd, double theta_deg,
                   double theta_sd_deg) {
  Transition& a = m.a(from, to);
  a.p = p;
  a.count = 1.0;
  a.t_mean = t;
  a.t_sd = t_sd;
  a.theta_mean = theta_deg * kDeg;
  a.theta_sd = theta_sd_deg * kDeg;
  a.azimuth.fill(1.0 / kAzimuthBins);
}

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", x);
  return buf;
}

}  // namespace

PlantonModel ground_truth_model() {
  PlantonModel m;
  for (int t = 0; t < kOrganTypes; ++t) {
    size_t d = size_t(organ_param_count(OrganType(t)));
    m.scales[size_t(t)].mean.assign(d, 0.0);
    m.scales[size_t(t)].alpha.assign(d, 1.0);
  }
  m.plantons.push_back(gt_stem({8.0, 0.3, 0.22, 0.07, 0.0, 6.0, 0.5}));    // T
  m.plantons.push_back(gt_stem({3.0, 0.2, 0.06, 0.02, 0.04, 4.0, 0.5}));   // P
  m.plantons.push_back(gt_stem({1.0, 0.1, 0.018, 0.006, 0.03, 5.0, 0.5}));  // S
  Planton leaf;
  leaf.type = OrganType::Leaf;
  leaf.mean = {0.3};
  leaf.covariance = {0.03 * 0.03};
  m.plantons.push_back(leaf);  // L
  m.transitions.assign(16, Transition{});
  gt_transition(m, 0, 1, 1.0, 0.6, 0.15, 50.0, 5.0);
  gt_transition(m, 1, 2, 0.75, 0.55, 0.2, 45.0, 5.0);
  gt_transition(m, 1, 3, 0.25, 0.7, 0.2, 60.0, 10.0);
  gt_transition(m, 2, 3, 1.0, 0.6, 0.25, 55.0, 10.0);
  m.root_planton = 0;
  m.root_theta_mean = 0.0;
  m.root_theta_sd = 0.02;
  return m;
}

std::vector<OrganTree> ground_truth_samples(size_t count, uint64_t seed, std::vector<std::vector<uint32_t>>* truth) {
  PlantonModel gt = ground_truth_model();
  std::vector<OrganTree> out;
  if (truth) truth->clear();
  for (size_t i = 0; i < count; ++i) {
    SynthesizedTree s = synthesize_plantons(gt, {}, seed + i);
    out.push_back(std::move(s.tree));
    if (truth) truth->push_back(std::move(s.plantons));
  }
  return out;
}

std::vector<TreeGraph> species_samples(const std::vector<std::filesystem::path>& species, size_t count, uint64_t seed) {
  std::vector<TreeGraph> out;
  for (const auto& file : species)
    for (size_t k = 0; k < count; ++k) {
      GenerateOptions options;
      options.seed = seed + k;
      TreeGraph graph;
      options.skeleton = &graph;
      generate_from_species(file, options);
      out.push_back(std::move(graph));
    }
  return out;
}

std::string samples_to_text(const std::vector<TreeGraph>& trees) {
  std::string out = "{\"format\": \"forest-samples\", \"version\": 1, \"trees\": [";
  for (size_t t = 0; t < trees.size(); ++t) {
    out += t ? ",\n {\"nodes\": [" : "\n {\"nodes\": [";
    const TreeGraph& g = trees[t];
    for (size_t i = 0; i < g.nodes.size(); ++i) {
      const TreeNode& n = g.nodes[i];
      out += (i ? ",\n  [" : "\n  [") + fmt(n.position.x) + ", " + fmt(n.position.y) + ", " + fmt(n.position.z) +
             ", " + fmt(n.radius) + ", " + std::to_string(n.parent) + ", " + std::to_string(n.order) + "]";
    }
    out += "],\n  \"leaves\": [";
    for (size_t i = 0; i < g.leaves.size(); ++i) {
      const LeafPlacement& l = g.leaves[i];
      out += (i ? ",\n  [" : "\n  [") + fmt(l.position.x) + ", " + fmt(l.position.y) + ", " + fmt(l.position.z) +
             ", " + fmt(l.rotation.w) + ", " + fmt(l.rotation.x) + ", " + fmt(l.rotation.y) + ", " +
             fmt(l.rotation.z) + ", " + fmt(l.scale) + "]";
    }
    out += "]}";
  }
  out += "\n]}\n";
  return out;
}

void save_samples(const std::vector<TreeGraph>& trees, const std::filesystem::path& path) {
  std::string text = samples_to_text(trees);
  write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

namespace {
// A JSON array of exactly `n` finite numbers, none beyond 1e6 in magnitude.
bool finite_numbers(const nlohmann::json& a, size_t n) {
  if (!a.is_array() || a.size() != n) return false;
  for (const nlohmann::json& v : a)
    if (!v.is_number() || !std::isfinite(v.get<double>()) || std::abs(v.get<double>()) > 1e6) return false;
  return true;
}
}  // namespace

std::vector<TreeGraph> parse_samples(const std::string& text, const std::string& name) {
  using nlohmann::json;
  auto line_at = [&](size_t offset) {
    int line = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
    return line;
  };
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(name, line_at(e.byte > 0 ? e.byte - 1 : 0), "", std::string("JSON syntax: ") + e.what());
  } catch (const json::exception& e) {  // e.g. out_of_range.406: a number beyond double
    throw InputError(name, 0, "", std::string("JSON: ") + e.what());
  }
  if (!j.is_object() || j.value("format", "") != "forest-samples")
    throw InputError(name, 1, "format", "must be \"forest-samples\"");
  if (j.value("version", 0) != 1) throw InputError(name, 1, "version", "must be 1");
  auto trees = j.find("trees");
  if (trees == j.end() || !trees->is_array() || trees->empty())
    throw InputError(name, 1, "trees", "must be a non-empty array of trees");
  std::vector<TreeGraph> out;
  size_t total = 0;
  for (size_t t = 0; t < trees->size(); ++t) {
    const json& tree = (*trees)[t];
    const std::string key = "trees[" + std::to_string(t) + "]";
    auto fail = [&](const std::string& k, const std::string& what) -> void { throw InputError(name, 0, key + k, what); };
    if (!tree.is_object() || !tree.contains("nodes") || !tree["nodes"].is_array()) fail(".nodes", "missing or not an array");
    TreeGraph g;
    const json& nodes = tree["nodes"];
    total += nodes.size();
    if (total > kMaxSampleNodes) fail(".nodes", "more than " + std::to_string(kMaxSampleNodes) + " nodes in all");
    for (size_t i = 0; i < nodes.size(); ++i) {
      const json& n = nodes[i];
      const std::string nk = ".nodes[" + std::to_string(i) + "]";
      if (!finite_numbers(n, 6)) fail(nk, "must be [x, y, z, radius, parent, order] of finite numbers (|x| <= 1e6)");
      TreeNode node;
      node.position = {n[0].get<float>(), n[1].get<float>(), n[2].get<float>()};
      node.radius = n[3].get<float>();
      double parent = n[4].get<double>(), order = n[5].get<double>();
      if (node.radius < 0.0f) fail(nk, "radius must be >= 0");
      if (parent != std::floor(parent) || parent >= double(i) || (i == 0 ? parent != -1 : parent < 0))
        fail(nk, "parent must be an integer below the node's index (-1 for node 0 only)");
      if (order != std::floor(order) || order < 0) fail(nk, "order must be an integer >= 0");
      node.parent = int32_t(parent);
      node.order = uint32_t(order);
      g.nodes.push_back(node);
    }
    if (g.nodes.size() < 2) fail(".nodes", "a sample tree needs at least 2 nodes");
    if (tree.contains("leaves")) {
      const json& leaves = tree["leaves"];
      if (!leaves.is_array()) fail(".leaves", "must be an array");
      for (size_t i = 0; i < leaves.size(); ++i) {
        const json& l = leaves[i];
        const std::string lk = ".leaves[" + std::to_string(i) + "]";
        if (!finite_numbers(l, 8)) fail(lk, "must be [x, y, z, qw, qx, qy, qz, scale] of finite numbers (|x| <= 1e6)");
        LeafPlacement p;
        p.position = {l[0].get<float>(), l[1].get<float>(), l[2].get<float>()};
        p.rotation = glm::quat(l[3].get<float>(), l[4].get<float>(), l[5].get<float>(), l[6].get<float>());
        float qn = glm::length(p.rotation);
        if (!(qn > 1e-3f)) fail(lk, "rotation must be a non-zero quaternion");
        p.rotation = p.rotation / qn;
        p.scale = l[7].get<float>();
        if (!(p.scale > 0.0f)) fail(lk, "scale must be > 0");
        g.leaves.push_back(p);
      }
    }
    out.push_back(std::move(g));
  }
  return out;
}

std::vector<TreeGraph> load_samples(const std::filesystem::path& path) {
  return parse_samples(read_text_file(path, "sample file"), path.string());
}

void plantons_make_inputs(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create folder: " + ec.message());
  std::vector<TreeGraph> graphs;
  for (const OrganTree& t : ground_truth_samples(3, 1)) graphs.push_back(graph_from_organs(t));
  save_samples(graphs, dir / "ground_truth.json");
}

}  // namespace forest
