// Per-model pruning tables measured with Precision/Recall (Neubert 2012 §7.2): s_opt(λ) at
// equidistant λ and λ_opt(d) at the distances of prune::d_sample(), plus the quality values
// behind them. Stored in extras.forest.pr_tables of a baked .glb.
//
// The sample positions are not stored here: λ_i = pr_lambda(i), d_j = pr_d(j) and
// λ_Cook(d_j) = pr_lambda_cook(j) follow from the index. The asset still carries them (keys
// lambda, d, lambda_cook, for people and plots); the reader checks them against these.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu_types.h"

namespace forest {

struct PrTables {
  std::vector<float> s_opt;        // S_SAMPLES: area scale maximizing Q at each λ (7.6)
  std::vector<float> q_opt;        // S_SAMPLES: Q(λ, s_opt(λ)) (7.7)
  std::vector<float> q_inverse;    // S_SAMPLES: Q(λ, 1/λ), Cook's area preservation
  std::vector<float> lambda_opt;   // D_SAMPLES: smallest λ with Q(λ, s_opt) >= Q(λ_Cook(d), 1/λ_Cook)
  std::string priority;            // leaf order the tables were measured with ("" = not recorded)
  int views = 0;                   // views averaged
  int resolution = 0;              // pixels of each coverage render
};

float pr_lambda(uint32_t i);       // λ of s_opt sample i < S_SAMPLES: i / (S_SAMPLES − 1)
float pr_d(uint32_t j);            // normalized distance of λ_opt sample j < D_SAMPLES: prune::d_sample(j)
float pr_lambda_cook(uint32_t j);  // Cook's λ at pr_d(j): (1 − d)²

// extras.forest.pr_tables, derived keys (lambda, d, lambda_cook) included.
nlohmann::json to_json(const PrTables& t);
// Reads an extras.forest.pr_tables object; InputError naming `name` and
// extras.forest.pr_tables.<key> for a wrong size, a non-number, a value out of range or a
// derived value that disagrees with its derivation.
PrTables pr_tables_from_json(const nlohmann::json& j, const std::string& name);

}  // namespace forest
