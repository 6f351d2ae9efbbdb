// extras.forest <-> BakeData. Number types follow what the bake always wrote, so that a model
// encodes to the same bytes as before the data was typed: floats as JSON doubles of the float,
// precision and recall as doubles, views and resolution as integers, baked as true.
#include "generators/asset/bake_data.h"

#include <cmath>
#include <stdexcept>

#include "generators/bake/priority/priority_names.h"
#include "generators/core/input_error.h"

namespace forest {

namespace {

nlohmann::json points_json(const std::vector<glm::vec3>& points) {
  nlohmann::json a = nlohmann::json::array();
  for (const glm::vec3& p : points) a.push_back({p.x, p.y, p.z});
  return a;
}

struct BakeReader {
  nlohmann::json& forest;
  const std::string& name;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(name, 0, "extras.forest." + key, what);
  }

  // The value of `key`, moved out of extras.forest (nullopt when absent).
  std::optional<nlohmann::json> take(const char* key) const {
    auto it = forest.find(key);
    if (it == forest.end()) return std::nullopt;
    nlohmann::json v = std::move(*it);
    forest.erase(it);
    return v;
  }

  // A finite number in [lo, hi] (checked as a double: narrowing a larger one is undefined).
  double number(const nlohmann::json& v, const std::string& key, double lo, double hi) const {
    if (!v.is_number()) fail(key, "expected a number");
    double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      fail(key, "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(x));
    return x;
  }

  std::vector<glm::vec3> points(const nlohmann::json& list, const char* key) const {
    if (!list.is_array()) fail(key, "expected an array of [x, y, z]");
    if (list.size() > kMaxHullSamples)
      fail(key, std::to_string(list.size()) + " points, more than the limit of " + std::to_string(kMaxHullSamples));
    std::vector<glm::vec3> out;
    out.reserve(list.size());
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
      const nlohmann::json& v = list[i];
      if (!v.is_array() || v.size() != 3) fail(at, "expected [x, y, z] of finite numbers");
      glm::vec3 p;
      for (int k = 0; k < 3; ++k) p[k] = float(number(v[size_t(k)], at, -1e9, 1e9));
      out.push_back(p);
    }
    return out;
  }

  std::optional<HullSamples> hull() const {
    std::optional<nlohmann::json> pts = take("hull_samples"), nrm = take("hull_sample_normals"),
                                   iso = take("hull_iso"), radius = take("hull_radius");
    if (!pts && !nrm && !iso && !radius) return std::nullopt;
    auto need = [&](const std::optional<nlohmann::json>& v, const char* key) {
      if (!v) fail(key, "missing: the hull keys (hull_samples, hull_sample_normals, hull_iso, hull_radius) come together");
    };
    need(pts, "hull_samples"), need(nrm, "hull_sample_normals"), need(iso, "hull_iso"), need(radius, "hull_radius");
    HullSamples h;
    h.points = points(*pts, "hull_samples");
    h.normals = points(*nrm, "hull_sample_normals");
    if (h.normals.size() != h.points.size())
      fail("hull_sample_normals", "expected one normal per hull sample: " + std::to_string(h.normals.size()) +
                                      " normals for " + std::to_string(h.points.size()) + " samples");
    for (size_t i = 0; i < h.normals.size(); ++i) {
      double len = glm::length(glm::dvec3(h.normals[i]));
      if (!(std::abs(len - 1.0) <= double(kUnitNormalTolerance)))
        fail("hull_sample_normals[" + std::to_string(i) + "]", "not unit length (length " + std::to_string(len) + ")");
    }
    h.iso = float(number(*iso, "hull_iso", 0.0, 1.0));
    if (!(h.iso > 0.0f && h.iso < 1.0f)) fail("hull_iso", "expected a number in (0, 1)");
    h.radius = float(number(*radius, "hull_radius", 0.0, 1e9));
    if (!(h.radius > 0.0f)) fail("hull_radius", "expected a positive number");
    return h;
  }

  std::string order_name(const nlohmann::json& v, const std::string& key) const {
    if (!v.is_string()) fail(key, "is not a string");
    std::string s = v.get<std::string>();
    if (!parse_priority(s)) fail(key, "unknown priority '" + s + "' (random, density, orientation, combined, layered)");
    return s;
  }

  std::vector<PrPoint> pr_samples(const nlohmann::json& list) const {
    if (!list.is_array()) fail("pr_samples", "expected an array of [lambda, s, size, precision, recall]");
    std::vector<PrPoint> out;
    out.reserve(list.size());
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string at = "pr_samples[" + std::to_string(i) + "]";
      const nlohmann::json& v = list[i];
      if (!v.is_array() || v.size() != 5) fail(at, "expected [lambda, s, size, precision, recall] numbers");
      PrPoint p;
      p.lambda = float(number(v[0], at, 0.0, 1.0));
      p.scale = float(number(v[1], at, 0.0, 1e4));
      p.size = float(number(v[2], at, 0.0, 65536.0));
      p.precision = number(v[3], at, 0.0, 1.0);
      p.recall = number(v[4], at, 0.0, 1.0);
      out.push_back(p);
    }
    return out;
  }
};

}  // namespace

void bake_to_json(const BakeData& bake, nlohmann::json& forest) {
  for (const char* key : kBakeKeys)
    if (forest.contains(key))
      throw std::logic_error(std::string("extras.forest.") + key + " is bake data: set it in TreeModel::bake, not in meta");
  if (!bake.pr_tables && !bake.pr_samples.empty())
    throw std::logic_error("bake data: pr_samples without pr_tables");
  if (bake.hull) {
    forest["hull_samples"] = points_json(bake.hull->points);
    forest["hull_sample_normals"] = points_json(bake.hull->normals);
    forest["hull_iso"] = bake.hull->iso;
    forest["hull_radius"] = bake.hull->radius;
  }
  // The depths are per-leaf attributes of the leaves node (glb_writer.cpp); κ is the key.
  if (bake.crown) forest["crown_extinction"] = bake.crown->extinction;
  if (!bake.priority.empty()) forest["priority"] = bake.priority;
  if (bake.pr_tables) {
    forest["pr_tables"] = to_json(*bake.pr_tables);
    nlohmann::json samples = nlohmann::json::array();  // the PR diagram behind the tables
    for (const PrPoint& p : bake.pr_samples) samples.push_back({p.lambda, p.scale, p.size, p.precision, p.recall});
    forest["pr_samples"] = std::move(samples);
    forest["baked"] = true;
  }
}

BakeData bake_from_json(nlohmann::json& forest, const std::string& name) {
  if (!forest.is_object()) throw InputError(name, 0, "extras.forest", "expected an object");
  BakeReader r{forest, name};
  BakeData b;
  b.hull = r.hull();
  if (auto v = r.take("crown_extinction")) {
    // decode_glb pairs it with the leaves' _CROWN_DEPTH_* attributes (one without the other
    // is refused there).
    b.crown = CrownLight{};
    b.crown->extinction = float(r.number(*v, "crown_extinction", 0.0, kMaxCrownExtinctionOnLoad));
    if (!(b.crown->extinction > 0.0f)) r.fail("crown_extinction", "expected a positive number");
  }
  if (auto v = r.take("priority")) b.priority = r.order_name(*v, "priority");
  std::optional<nlohmann::json> tables = r.take("pr_tables"), samples = r.take("pr_samples"), baked = r.take("baked");
  if (tables) {
    b.pr_tables = pr_tables_from_json(*tables, name);
    const std::string& measured = b.pr_tables->priority;
    if (!measured.empty()) {
      r.order_name(measured, "pr_tables.priority");
      if (measured != b.priority)
        r.fail("pr_tables.priority", "tables measured with the " + measured + " order, but the leaves are in " +
                                         (b.priority.empty() ? "generation order" : "the " + b.priority + " order"));
    }
  }
  // Derived: baked is true exactly when there are tables; the PR diagram comes with them.
  if (baked && !(baked->is_boolean() && baked->get<bool>()))
    r.fail("baked", "expected true (it is written with pr_tables only)");
  if (bool(baked) != bool(tables))
    r.fail(tables ? "baked" : "pr_tables", tables ? "missing: expected true with pr_tables" : "missing: baked is true");
  if (bool(samples) != bool(tables))
    r.fail(tables ? "pr_samples" : "pr_tables", tables ? "missing: expected with pr_tables" : "missing: pr_samples come with it");
  if (samples) b.pr_samples = r.pr_samples(*samples);
  return b;
}

}  // namespace forest
