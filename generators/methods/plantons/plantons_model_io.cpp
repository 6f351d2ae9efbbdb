// The planton model file: JSON, one planton / transition per line so that a message can name
// the line of the element at fault.
#include <cctype>
#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "generators/asset/asset_io.h"
#include "generators/core/limits.h"
#include "generators/core/input_error.h"
#include "generators/core/text_file.h"
#include "generators/methods/plantons/plantons_model.h"

namespace forest {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "forest-plantons";
constexpr int kVersion = 1;

double round7(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", x);
  return std::strtod(buf, nullptr);
}

json vec_json(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(round7(x));
  return a;
}

const char* type_key(OrganType t) { return organ_type_name(t); }

int line_at(const std::string& text, size_t offset) {
  int line = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i)
    if (text[i] == '\n') ++line;
  return line;
}

// Index just past the JSON value starting at text[i] (strings and nesting only; the text has
// already been parsed successfully).
size_t skip_value(const std::string& text, size_t i) {
  int depth = 0;
  bool in_string = false;
  for (; i < text.size(); ++i) {
    char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') {
        in_string = false;
        if (depth == 0) return i + 1;
      }
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '{' || c == '[') ++depth;
    else if (c == '}' || c == ']') {
      if (depth == 0) return i;  // end of the enclosing array: a scalar ended here
      if (--depth == 0) return i + 1;
    } else if (c == ',' && depth == 0) return i;
  }
  return i;
}

// Offset of element `index` of the top-level array `key`; npos when not found.
size_t element_offset(const std::string& text, const std::string& key, size_t index) {
  size_t i = text.find('{');
  if (i == std::string::npos) return std::string::npos;
  const std::string quoted = "\"" + key + "\"";
  ++i;
  // Walk the top-level members: "key": value, ...
  while (i < text.size()) {
    while (i < text.size() && (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ',')) ++i;
    if (i >= text.size() || text[i] != '"') return std::string::npos;
    bool match = text.compare(i, quoted.size(), quoted) == 0;
    i = skip_value(text, i);
    while (i < text.size() && text[i] != ':') ++i;
    ++i;
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (!match) {
      i = skip_value(text, i);
      continue;
    }
    if (i >= text.size() || text[i] != '[') return std::string::npos;
    ++i;
    for (size_t count = 0; i < text.size(); ++count) {
      while (i < text.size() && (std::isspace(static_cast<unsigned char>(text[i])) || text[i] == ',')) ++i;
      if (i >= text.size() || text[i] == ']') return std::string::npos;
      if (count == index) return i;
      i = skip_value(text, i);
    }
    return std::string::npos;
  }
  return std::string::npos;
}

struct Reader {
  const std::string& text;
  const std::string& name;

  [[noreturn]] void fail(const std::string& key, const std::string& what, int line = 0) const {
    if (line == 0) {
      size_t at = text.find("\"" + key.substr(0, key.find_first_of(".[")) + "\"");
      line = at == std::string::npos ? 0 : line_at(text, at);
    }
    throw InputError(name, line, key, what);
  }
  int element_line(const std::string& array, size_t i) const {
    size_t at = element_offset(text, array, i);
    return at == std::string::npos ? 0 : line_at(text, at);
  }
};

const json& field(const Reader& r, const json& obj, const std::string& key, const std::string& path, int line) {
  if (!obj.is_object()) r.fail(path, "must be an object", line);
  auto it = obj.find(key);
  if (it == obj.end()) r.fail(path.empty() ? key : path + "." + key, "missing", line);
  return *it;
}

double number(const Reader& r, const json& v, const std::string& path, int line, double lo, double hi) {
  if (!v.is_number()) r.fail(path, "must be a number", line);
  double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    r.fail(path, "must be a finite number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", line);
  return x;
}

std::vector<double> numbers(const Reader& r, const json& v, const std::string& path, int line, size_t size,
                            double lo, double hi) {
  if (!v.is_array() || v.size() != size) r.fail(path, "must be an array of " + std::to_string(size) + " numbers", line);
  std::vector<double> out;
  for (size_t i = 0; i < size; ++i) out.push_back(number(r, v[i], path + "[" + std::to_string(i) + "]", line, lo, hi));
  return out;
}

OrganType type_of(const Reader& r, const json& v, const std::string& path, int line) {
  if (v == "stem") return OrganType::Stem;
  if (v == "leaf") return OrganType::Leaf;
  r.fail(path, "must be \"stem\" or \"leaf\"", line);
}

}  // namespace

json model_to_json(const PlantonModel& m) {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["regularization"] = round7(m.regularization);
  j["damping"] = round7(m.damping);
  j["root_planton"] = m.root_planton;
  j["root_theta"] = {round7(m.root_theta_mean), round7(m.root_theta_sd)};
  for (int t = 0; t < kOrganTypes; ++t)
    j["scales"][type_key(OrganType(t))] = {{"mean", vec_json(m.scales[size_t(t)].mean)},
                                           {"alpha", vec_json(m.scales[size_t(t)].alpha)}};
  j["plantons"] = json::array();
  for (const Planton& x : m.plantons) {
    json e;
    e["type"] = type_key(x.type);
    e["organs"] = x.organ_count;
    e["mean"] = vec_json(x.mean);
    e["covariance"] = vec_json(x.covariance);
    e["children"] = {round7(x.child_mean), round7(x.child_sd)};
    e["exemplars"] = json::array();
    for (const auto& s : x.exemplars) e["exemplars"].push_back(vec_json(s));
    j["plantons"].push_back(e);
  }
  j["transitions"] = json::array();
  for (size_t a = 0; a < m.N(); ++a)
    for (size_t b = 0; b < m.N(); ++b) {
      const Transition& t = m.a(a, b);
      if (t.count <= 0.0 && t.p <= 0.0) continue;
      std::vector<double> az(t.azimuth.begin(), t.azimuth.end());
      j["transitions"].push_back({{"from", a}, {"to", b}, {"count", round7(t.count)}, {"p", round7(t.p)},
                                  {"t", {round7(t.t_mean), round7(t.t_sd)}},
                                  {"theta", {round7(t.theta_mean), round7(t.theta_sd)}},
                                  {"azimuth", vec_json(az)}});
    }
  return j;
}

std::string model_to_text(const PlantonModel& model, const json& provenance) {
  json j = model_to_json(model);
  j["provenance"] = provenance;
  // Scalars and small objects one per line; the two arrays one element per line.
  std::string out = "{\n";
  bool first = true;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (!first) out += ",\n";
    first = false;
    out += "  " + json(it.key()).dump() + ": ";
    if (it.key() == "plantons" || it.key() == "transitions") {
      out += "[";
      for (size_t i = 0; i < it->size(); ++i) out += (i ? ",\n    " : "\n    ") + (*it)[i].dump();
      out += it->empty() ? "]" : "\n  ]";
    } else {
      out += it->dump();
    }
  }
  out += "\n}\n";
  return out;
}

void save_model(const PlantonModel& model, const json& provenance, const std::filesystem::path& path) {
  std::string text = model_to_text(model, provenance);
  write_file_atomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

PlantonModel parse_model(const std::string& text, const std::string& name) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(name, line_at(text, e.byte > 0 ? e.byte - 1 : 0), "", std::string("JSON syntax: ") + e.what());
  } catch (const json::exception& e) {  // e.g. out_of_range.406: a number beyond double
    throw InputError(name, 0, "", std::string("JSON: ") + e.what());
  }
  Reader r{text, name};
  if (!j.is_object()) r.fail("", "the model must be a JSON object", 1);
  if (field(r, j, "format", "", 0) != kFormat) r.fail("format", std::string("must be \"") + kFormat + "\"");
  if (field(r, j, "version", "", 0) != kVersion) r.fail("version", "must be " + std::to_string(kVersion));
  PlantonModel m;
  m.regularization = number(r, field(r, j, "regularization", "", 0), "regularization", 0, 0.0, 1e6);
  m.damping = number(r, field(r, j, "damping", "", 0), "damping", 0, 0.0, 1.0);
  std::vector<double> rt = numbers(r, field(r, j, "root_theta", "", 0), "root_theta", 0, 2, 0.0, 4.0);
  m.root_theta_mean = rt[0];
  m.root_theta_sd = rt[1];
  const json& scales = field(r, j, "scales", "", 0);
  for (int t = 0; t < kOrganTypes; ++t) {
    const std::string key = std::string("scales.") + type_key(OrganType(t));
    const json& s = field(r, scales, type_key(OrganType(t)), "scales", 0);
    const size_t d = size_t(organ_param_count(OrganType(t)));
    m.scales[size_t(t)].mean = numbers(r, field(r, s, "mean", key, 0), key + ".mean", 0, d, -1e9, 1e9);
    m.scales[size_t(t)].alpha = numbers(r, field(r, s, "alpha", key, 0), key + ".alpha", 0, d, 0.0, 1e18);
  }
  const json& plantons = field(r, j, "plantons", "", 0);
  if (!plantons.is_array() || plantons.empty() || plantons.size() > kMaxPlantons)
    r.fail("plantons", "must be an array of 1 to " + std::to_string(kMaxPlantons) + " plantons");
  const size_t n = plantons.size();
  size_t exemplars = 0;
  for (size_t i = 0; i < n; ++i) {
    const std::string key = "plantons[" + std::to_string(i) + "]";
    const int line = r.element_line("plantons", i);
    const json& e = plantons[i];
    Planton x;
    x.type = type_of(r, field(r, e, "type", key, line), key + ".type", line);
    const size_t d = size_t(organ_param_count(x.type));
    x.organ_count = size_t(number(r, field(r, e, "organs", key, line), key + ".organs", line, 0.0, 1e9));
    x.mean = numbers(r, field(r, e, "mean", key, line), key + ".mean", line, d, -1e9, 1e9);
    x.covariance = numbers(r, field(r, e, "covariance", key, line), key + ".covariance", line, d * d, -1e18, 1e18);
    Eigen::MatrixXd cov = Eigen::Map<const Eigen::MatrixXd>(x.covariance.data(), Eigen::Index(d), Eigen::Index(d));
    if (!cov.isApprox(cov.transpose()) || cov.llt().info() != Eigen::Success)
      r.fail(key + ".covariance", "must be symmetric positive definite", line);
    std::vector<double> ch = numbers(r, field(r, e, "children", key, line), key + ".children", line, 2, 0.0, 1e4);
    x.child_mean = ch[0];
    x.child_sd = ch[1];
    const json& ex = field(r, e, "exemplars", key, line);
    if (!ex.is_array()) r.fail(key + ".exemplars", "must be an array", line);
    exemplars += ex.size();
    if (exemplars > kMaxPlantonExemplars) r.fail(key + ".exemplars", "more than 2000000 exemplars in all", line);
    for (size_t k = 0; k < ex.size(); ++k) {
      std::vector<double> s = numbers(r, ex[k], key + ".exemplars[" + std::to_string(k) + "]", line, d, -1e6, 1e6);
      if (!(s[0] > 0.0)) r.fail(key + ".exemplars[" + std::to_string(k) + "]", "length must be > 0", line);
      x.exemplars.push_back(std::move(s));
    }
    m.plantons.push_back(std::move(x));
  }
  m.transitions.assign(n * n, Transition{});
  const json& transitions = field(r, j, "transitions", "", 0);
  if (!transitions.is_array()) r.fail("transitions", "must be an array");
  for (size_t i = 0; i < transitions.size(); ++i) {
    const std::string key = "transitions[" + std::to_string(i) + "]";
    const int line = r.element_line("transitions", i);
    const json& e = transitions[i];
    size_t from = size_t(number(r, field(r, e, "from", key, line), key + ".from", line, 0, double(n - 1)));
    size_t to = size_t(number(r, field(r, e, "to", key, line), key + ".to", line, 0, double(n - 1)));
    if (m.plantons[from].type == OrganType::Leaf) r.fail(key + ".from", "a leaf planton has no children", line);
    Transition& t = m.a(from, to);
    t.count = number(r, field(r, e, "count", key, line), key + ".count", line, 0.0, 1e12);
    t.p = number(r, field(r, e, "p", key, line), key + ".p", line, 0.0, 1.0);
    std::vector<double> tt = numbers(r, field(r, e, "t", key, line), key + ".t", line, 2, -1e3, 1e3);
    std::vector<double> th = numbers(r, field(r, e, "theta", key, line), key + ".theta", line, 2, -10.0, 10.0);
    std::vector<double> az = numbers(r, field(r, e, "azimuth", key, line), key + ".azimuth", line, kAzimuthBins, 0.0, 1.0);
    if (tt[1] < 0.0 || th[1] < 0.0) r.fail(key, "standard deviations must be >= 0", line);
    t.t_mean = tt[0];
    t.t_sd = tt[1];
    t.theta_mean = th[0];
    t.theta_sd = th[1];
    double az_sum = 0.0;
    for (int b = 0; b < kAzimuthBins; ++b) az_sum += t.azimuth[size_t(b)] = az[size_t(b)];
    if (std::abs(az_sum - 1.0) > 1e-4) r.fail(key + ".azimuth", "must sum to 1", line);
  }
  for (size_t a = 0; a < n; ++a) {
    double row = 0.0;
    for (size_t b = 0; b < n; ++b) row += m.a(a, b).p;
    bool has_children = m.plantons[a].type == OrganType::Stem && (m.plantons[a].child_mean > 0.0 || m.plantons[a].child_sd > 0.0);
    if (has_children ? std::abs(row - 1.0) > 1e-4 : row != 0.0)
      r.fail("transitions", "the probabilities p from planton " + std::to_string(a) + " sum to " + std::to_string(row) +
                                (has_children ? " instead of 1" : " but it has no children"));
  }
  m.root_planton = uint32_t(number(r, field(r, j, "root_planton", "", 0), "root_planton", 0, 0.0, double(n - 1)));
  if (m.plantons[m.root_planton].type != OrganType::Stem) r.fail("root_planton", "must be a stem planton");
  double rho = spectral_radius(offspring_matrix(m), n);
  if (rho >= 1.0)
    r.fail("plantons", "supercritical model: the expected-offspring matrix has spectral radius " + std::to_string(rho) +
                           " >= 1 (trees would grow without bound)");
  return m;
}

PlantonModel load_model(const std::filesystem::path& path) {
  return parse_model(read_text_file(path, "planton model file"), path.string());
}

}  // namespace forest
