// Per-model pruning tables measured with Precision/Recall (Neubert 2012 §7.2): s_opt(λ) at
// equidistant λ and λ_opt(d) at the distances of prune::d_sample(), plus the quality values
// behind them. Stored in extras.forest.pr_tables of a baked .glb.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu_types.h"

namespace forest {

struct PrTables {
  std::vector<float> lambda;       // S_SAMPLES values i/(S_SAMPLES-1)
  std::vector<float> s_opt;        // S_SAMPLES: area scale maximizing Q at each λ (7.6)
  std::vector<float> q_opt;        // S_SAMPLES: Q(λ, s_opt(λ)) (7.7)
  std::vector<float> q_inverse;    // S_SAMPLES: Q(λ, 1/λ), Cook's area preservation
  std::vector<float> d;            // D_SAMPLES distances
  std::vector<float> lambda_opt;   // D_SAMPLES: smallest λ with Q(λ, s_opt) >= Q(λ_Cook(d), 1/λ_Cook)
  std::vector<float> lambda_cook;  // D_SAMPLES: (1 - d)^2 for comparison
  std::string priority;            // leaf order the tables were measured with
  int views = 0;                   // views averaged
  int resolution = 0;              // pixels of each coverage render
};

nlohmann::json to_json(const PrTables& t);
// Reads extras.forest.pr_tables: nullopt when absent; InputError (naming `name`) when malformed.
std::optional<PrTables> read_pr_tables(const nlohmann::json& meta, const std::string& name);

}  // namespace forest
