#include "generators/asset/pr_tables.h"

#include <algorithm>
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
float pr_lambda_far(uint32_t f) { return prune::far_lambda(f); }
float pr_size(float size0, uint32_t b) { return std::ldexp(size0, -int(b)); }

float low_quantile(std::vector<float> q, double fraction) {
  if (q.empty()) return 1.0f;
  auto at = q.begin() + std::ptrdiff_t(std::clamp(fraction, 0.0, 1.0) * double(q.size() - 1));
  std::nth_element(q.begin(), at, q.end());
  return *at;
}

PrTables pr_tables_at_every_size(const PrSizeTables& one, float size0) {
  PrTables t;
  t.size0 = size0;
  t.sizes.assign(PR_SIZES, one);
  return t;
}

nlohmann::json to_json(const PrTables& t) {
  nlohmann::json per_size = nlohmann::json::array();
  std::vector<float> sizes;
  for (uint32_t b = 0; b < t.sizes.size(); ++b) {
    const PrSizeTables& s = t.sizes[b];
    sizes.push_back(pr_size(t.size0, b));
    per_size.push_back({{"size", sizes.back()},
                        {"s_opt", s.s_opt},
                        {"q_opt", s.q_opt},
                        {"q_inverse", s.q_inverse},
                        {"lambda_opt", s.lambda_opt},
                        {"s_far", s.s_far},
                        {"q_far", s.q_far},
                        {"q_inverse_far", s.q_inverse_far},
                        {"q_low", s.q_low},
                        {"q_low_far", s.q_low_far}});
  }
  return {{"format", kPrTablesFormat},
          {"lambda", derived(S_SAMPLES, pr_lambda)},
          {"d", derived(D_SAMPLES, pr_d)},
          {"lambda_cook", derived(D_SAMPLES, pr_lambda_cook)},
          {"lambda_far", derived(F_SAMPLES, pr_lambda_far)},
          {"size0", t.size0},
          {"sizes", sizes},
          {"per_size", per_size},
          {"priority", t.priority},
          {"views", t.views},
          {"resolution", t.resolution}};
}

PrTables pr_tables_from_json(const nlohmann::json& j, const std::string& name) {
  auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(name, 0, "extras.forest.pr_tables" + (key.empty() ? "" : "." + key), what);
  };
  if (!j.is_object()) fail("", "expected an object");
  if (!j.contains("format"))
    fail("format", "missing: PR tables of format 1 (measured at one size); generate the model again and bake it "
                   "(forest generate, forest bake; scenes re-bake their species by themselves)");
  if (!j["format"].is_number_integer() || j["format"].get<int64_t>() != kPrTablesFormat)
    fail("format", "expected " + std::to_string(kPrTablesFormat) + "; generate the model again and bake it (forest generate, forest bake)");
  // o[key], named `label` in messages.
  auto floats_of = [&](const nlohmann::json& o, const std::string& key, const std::string& label, size_t n, float lo,
                       float hi) {
    if (!o.contains(key) || !o[key].is_array() || o[key].size() != n)
      fail(label, "expected an array of " + std::to_string(n) + " numbers");
    std::vector<float> v;
    for (const auto& x : o[key]) {
      if (!x.is_number()) fail(label, "expected numbers");
      double f = x.get<double>();  // range-checked before narrowing: a huge double is no float
      if (!std::isfinite(f) || f < lo || f > hi)
        fail(label, "value out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      v.push_back(float(f));
    }
    return v;
  };
  auto floats = [&](const char* key, size_t n, float lo, float hi) { return floats_of(j, key, key, n, lo, hi); };
  // Derived keys: present, of the right size, and equal to their derivation.
  auto check_derived = [&](const std::string& key, const std::vector<float>& v, const std::vector<float>& want,
                           const char* formula) {
    for (size_t i = 0; i < v.size(); ++i)
      if (!(std::abs(double(v[i]) - double(want[i])) <= kDerivedTolerance * std::max(1.0, std::abs(double(want[i]))))) {
        char what[160];
        std::snprintf(what, sizeof(what), "%s[%zu] = %.9g, but %s gives %.9g", key.c_str(), i, double(v[i]), formula,
                      double(want[i]));
        fail(key, what);
      }
  };
  PrTables t;
  check_derived("lambda", floats("lambda", S_SAMPLES, 0.0f, 1.0f), derived(S_SAMPLES, pr_lambda), "i / (S_SAMPLES - 1)");
  check_derived("d", floats("d", D_SAMPLES, 0.0f, 1.0f), derived(D_SAMPLES, pr_d), "d_sample(j)");
  check_derived("lambda_cook", floats("lambda_cook", D_SAMPLES, 0.0f, 1.0f), derived(D_SAMPLES, pr_lambda_cook),
                "(1 - d_sample(j))^2");
  check_derived("lambda_far", floats("lambda_far", F_SAMPLES, 0.0f, 1.0f), derived(F_SAMPLES, pr_lambda_far),
                "1 / ((S_SAMPLES - 1) 2^(f+1))");
  if (!j.contains("size0") || !j["size0"].is_number() || !(j["size0"].get<double>() >= 1.0) ||
      !(j["size0"].get<double>() <= 65536.0))
    fail("size0", "expected a number of pixels in [1, 65536]");
  t.size0 = j["size0"].get<float>();
  std::vector<float> want_sizes;
  for (uint32_t b = 0; b < PR_SIZES; ++b) want_sizes.push_back(pr_size(t.size0, b));
  check_derived("sizes", floats("sizes", PR_SIZES, 0.0f, 65536.0f), want_sizes, "size0 / 2^b");
  if (!j.contains("per_size") || !j["per_size"].is_array() || j["per_size"].size() != PR_SIZES)
    fail("per_size", "expected an array of " + std::to_string(PR_SIZES) + " objects");
  for (uint32_t b = 0; b < PR_SIZES; ++b) {
    const nlohmann::json& o = j["per_size"][b];
    const std::string at = "per_size[" + std::to_string(b) + "]";
    if (!o.is_object()) fail(at, "expected an object");
    PrSizeTables s;
    s.s_opt = floats_of(o, "s_opt", at + ".s_opt", S_SAMPLES, 0.0f, 1e4f);
    s.q_opt = floats_of(o, "q_opt", at + ".q_opt", S_SAMPLES, -1.0f, 1.0f);
    s.q_inverse = floats_of(o, "q_inverse", at + ".q_inverse", S_SAMPLES, -1.0f, 1.0f);
    s.lambda_opt = floats_of(o, "lambda_opt", at + ".lambda_opt", D_SAMPLES, 0.0f, 1.0f);
    s.s_far = floats_of(o, "s_far", at + ".s_far", F_SAMPLES, 0.0f, 1e4f);
    s.q_far = floats_of(o, "q_far", at + ".q_far", F_SAMPLES, -1.0f, 1.0f);
    s.q_inverse_far = floats_of(o, "q_inverse_far", at + ".q_inverse_far", F_SAMPLES, -1.0f, 1.0f);
    s.q_low = floats_of(o, "q_low", at + ".q_low", S_SAMPLES, -1.0f, 1.0f);
    s.q_low_far = floats_of(o, "q_low_far", at + ".q_low_far", F_SAMPLES, -1.0f, 1.0f);
    t.sizes.push_back(std::move(s));
  }
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
