#include "generators/asset/pr_tables.h"

#include <cmath>

#include "generators/core/input_error.h"

namespace forest {

nlohmann::json to_json(const PrTables& t) {
  return {{"lambda", t.lambda},         {"s_opt", t.s_opt},   {"q_opt", t.q_opt},
          {"q_inverse", t.q_inverse},   {"d", t.d},           {"lambda_opt", t.lambda_opt},
          {"lambda_cook", t.lambda_cook}, {"priority", t.priority}, {"views", t.views},
          {"resolution", t.resolution}};
}

std::optional<PrTables> read_pr_tables(const nlohmann::json& meta, const std::string& name) {
  if (!meta.is_object() || !meta.contains("pr_tables")) return std::nullopt;
  const nlohmann::json& j = meta["pr_tables"];
  auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(name, 0, "extras.forest.pr_tables." + key, what);
  };
  if (!j.is_object()) fail("", "expected an object");
  auto floats = [&](const char* key, size_t n, float lo, float hi) {
    if (!j.contains(key) || !j[key].is_array() || j[key].size() != n)
      fail(key, "expected an array of " + std::to_string(n) + " numbers");
    std::vector<float> v;
    for (const auto& x : j[key]) {
      if (!x.is_number()) fail(key, "expected numbers");
      double f = x.get<double>();  // range-checked before narrowing: a huge double is no float
      if (!std::isfinite(f) || f < lo || f > hi) fail(key, "value out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      v.push_back(float(f));
    }
    return v;
  };
  PrTables t;
  t.lambda = floats("lambda", S_SAMPLES, 0.0f, 1.0f);
  t.s_opt = floats("s_opt", S_SAMPLES, 0.0f, 1e4f);
  t.q_opt = floats("q_opt", S_SAMPLES, -1.0f, 1.0f);
  t.q_inverse = floats("q_inverse", S_SAMPLES, -1.0f, 1.0f);
  t.d = floats("d", D_SAMPLES, 0.0f, 1.0f);
  t.lambda_opt = floats("lambda_opt", D_SAMPLES, 0.0f, 1.0f);
  t.lambda_cook = floats("lambda_cook", D_SAMPLES, 0.0f, 1.0f);
  if (j.contains("priority")) {
    if (!j["priority"].is_string()) fail("priority", "expected a string");
    t.priority = j["priority"].get<std::string>();
  }
  auto count = [&](const char* key) {
    if (!j.contains(key)) return 0;
    if (!j[key].is_number_integer() || j[key].get<int64_t>() < 0 || j[key].get<int64_t>() > 1'000'000)
      fail(key, "expected an integer in [0, 1000000]");
    return int(j[key].get<int64_t>());
  };
  t.views = count("views");
  t.resolution = count("resolution");
  return t;
}

}  // namespace forest
