// Per-model pruning tables measured with Precision/Recall (Neubert 2012 §7.2), per projected
// size: for each of PR_SIZES sizes p_b = size0 / 2^b (pixels across the bounding sphere),
// s_opt(λ) at equidistant λ and λ_opt(d) at the distances of prune::d_sample(), plus the
// quality values behind them. Q(λ, s) depends on the size at which a tree is seen (sub-pixel
// leaves merge), so the run time looks the tables up by the instance's projected size too.
// Stored in extras.forest.pr_tables of a baked .glb (format kPrTablesFormat).
//
// The sample positions are not stored here: λ_i = pr_lambda(i), d_j = pr_d(j),
// λ_Cook(d_j) = pr_lambda_cook(j), λ_f = pr_lambda_far(f) and p_b = pr_size(size0, b) follow
// from the index. The asset still carries them (keys lambda, d, lambda_cook, lambda_far, sizes,
// for people and plots); the reader checks them against these.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu_types.h"

namespace forest {

// 1: one size (resolution); 2: per projected size; 3: with s_opt and q_opt at the far λ below
// 1/20, and the low quantile q_low. Older formats are refused on load.
inline constexpr int kPrTablesFormat = 3;

// "Equal quality": Q ≥ Q_Cook − this, wherever a mode is judged against Cook et al. (the bench
// summary, the scene tests). PR counts are exact, but a frame's Q moves by about 0.001 with
// the sub-pixel placement of leaves; a real loss of quality is larger.
inline constexpr double kEqualQualityTolerance = 0.002;

// The tables of one projected size.
struct PrSizeTables {
  std::vector<float> s_opt;       // S_SAMPLES: area scale maximizing Q at each λ (7.6)
  std::vector<float> q_opt;       // S_SAMPLES: Q(λ, s_opt(λ)) (7.7)
  std::vector<float> q_inverse;   // S_SAMPLES: Q(λ, 1/λ), Cook's area preservation
  std::vector<float> lambda_opt;  // D_SAMPLES: smallest λ with Q(λ, s_opt) >= Q(λ_Cook(d), 1/λ_Cook)
  // The same three at the far λ_f = pr_lambda_far(f) below pr_lambda(1), f < F_SAMPLES.
  std::vector<float> s_far, q_far, q_inverse_far;
  // S_SAMPLES and F_SAMPLES: at each λ and its s_opt, the TARGET_LOW_QUANTILE quantile of Q
  // over the views and sub-pixel phases, each one what a single tree at this size may see.
  std::vector<float> q_low, q_low_far;
};

struct PrTables {
  std::vector<PrSizeTables> sizes;  // PR_SIZES: [b] measured at pr_size(size0, b)
  float size0 = 0.0f;               // pixels across the bounding sphere at sizes[0]
  std::string priority;             // leaf order the tables were measured with ("" = not recorded)
  int views = 0;                    // views averaged
  int resolution = 0;               // pixels of each (square) coverage render at sizes[0]
};

float pr_lambda(uint32_t i);       // λ of s_opt sample i < S_SAMPLES: i / (S_SAMPLES − 1)
float pr_d(uint32_t j);            // normalized distance of λ_opt sample j < D_SAMPLES: prune::d_sample(j)
float pr_lambda_cook(uint32_t j);  // Cook's λ at pr_d(j): (1 − d)²
float pr_lambda_far(uint32_t f);   // far λ sample f < F_SAMPLES: pr_lambda(1) / 2^(f+1)
float pr_size(float size0, uint32_t b);  // projected size of table size b < PR_SIZES: size0 / 2^b

// The low quantile of single-render Q values that q_low holds, and that the bench's per-tree
// figures are judged by: the value at rank ⌊fraction · (n − 1)⌋ of the sorted values (no
// interpolation between two renders' Q); 1 for none (nothing covered: nothing to lose).
float low_quantile(std::vector<float> q, double fraction = TARGET_LOW_QUANTILE);

// Tables holding `one` at every size (hand-made tables of tests and tools).
PrTables pr_tables_at_every_size(const PrSizeTables& one, float size0 = 512.0f);

// extras.forest.pr_tables, derived keys (lambda, d, lambda_cook, lambda_far, sizes) and format
// included.
nlohmann::json to_json(const PrTables& t);
// Reads an extras.forest.pr_tables object; InputError naming `name` and
// extras.forest.pr_tables.<key> for an older format, a wrong size, a non-number, a value out
// of range or a derived value that disagrees with its derivation.
PrTables pr_tables_from_json(const nlohmann::json& j, const std::string& name);

}  // namespace forest
