#include "generators/asset/pr_tables.h"

#include <cmath>
#include <cstdio>

#include "generators/core/input_error.h"
#include "prune_math.h"

namespace forest {

namespace {

// A stored derived value may differ from its derivation by this much (a hand-edited or
// differently rounded file); a larger difference means tables measured at other positions.
constexpr double kDerivedTolerance = 1e-5;

std::vector<float> derived(uint32_t n, float (*f)(uint32_t)) {
  std::vector<float> v(n);
  for (uint32_t i = 0; i < n; ++i) v[i] = f(i);
  return v;
}

}  // namespace

float pr_lambda(uint32_t i) { return float(i) / float(S_SAMPLES - 1); }
float pr_d(uint32_t j) { return prune::d_sample(j); }
float pr_lambda_cook(uint32_t j) { return prune::lambda_cook(prune::d_sample(j)); }

nlohmann::json to_json(const PrTables& t) {
  return {{"lambda", derived(S_SAMPLES, pr_lambda)},
          {"s_opt", t.s_opt},
          {"q_opt", t.q_opt},
          {"q_inverse", t.q_inverse},
          {"d", derived(D_SAMPLES, pr_d)},
          {"lambda_opt", t.lambda_opt},
          {"lambda_cook", derived(D_SAMPLES, pr_lambda_cook)},
          {"priority", t.priority},
          {"views", t.views},
          {"resolution", t.resolution}};
}

PrTables pr_tables_from_json(const nlohmann::json& j, const std::string& name) {
  auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(name, 0, "extras.forest.pr_tables" + (key.empty() ? "" : "." + key), what);
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
  // Derived keys: present, of the right size, and equal to their derivation.
  auto check_derived = [&](const char* key, uint32_t n, float (*f)(uint32_t), const char* formula) {
    std::vector<float> v = floats(key, n, 0.0f, 1.0f);
    for (uint32_t i = 0; i < n; ++i)
      if (!(std::abs(double(v[i]) - double(f(i))) <= kDerivedTolerance)) {
        char what[160];
        std::snprintf(what, sizeof(what), "%s[%u] = %.9g, but %s gives %.9g", key, i, double(v[i]), formula, double(f(i)));
        fail(key, what);
      }
  };
  PrTables t;
  check_derived("lambda", S_SAMPLES, pr_lambda, "i / (S_SAMPLES - 1)");
  t.s_opt = floats("s_opt", S_SAMPLES, 0.0f, 1e4f);
  t.q_opt = floats("q_opt", S_SAMPLES, -1.0f, 1.0f);
  t.q_inverse = floats("q_inverse", S_SAMPLES, -1.0f, 1.0f);
  check_derived("d", D_SAMPLES, pr_d, "d_sample(j)");
  t.lambda_opt = floats("lambda_opt", D_SAMPLES, 0.0f, 1.0f);
  check_derived("lambda_cook", D_SAMPLES, pr_lambda_cook, "(1 - d_sample(j))^2");
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
