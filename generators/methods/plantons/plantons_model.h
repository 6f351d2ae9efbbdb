// The two-level statistical tree model of Wang 2006 (§3.2): plantons
// x = (𝓛 cluster, 𝓖 Gaussian over the organ parameters, 𝓝 1D Gaussian over the child count)
// and transitions a[i, j] = (p, T, Ω). Also the organ distance D of eq. (1), the log
// likelihood of a labelling (eq. 5) that learning maximizes, the expected-offspring analysis
// synthesis relies on, and the model file (JSON).
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "generators/methods/plantons/plantons_organs.h"

namespace forest {

// Eq. (1) weights of one organ type: α_k = 1 / variance of parameter k over all sample
// organs of that type ([ours]; the paper gives none); a constant parameter gets α = 0.
// Organs are compared in z = √α (s − mean), where D is the squared Euclidean distance.
struct FeatureScale {
  std::vector<double> mean, alpha;
};
using FeatureScales = std::array<FeatureScale, kOrganTypes>;

FeatureScales feature_scales(const std::vector<OrganTree>& samples);
std::vector<double> to_z(const FeatureScale& scale, const std::vector<double>& s);
std::vector<double> from_z(const FeatureScale& scale, const std::vector<double>& z);  // α = 0: mean

// D(o_p, o_q) = Σ_k α_k (o_p.s[k] − o_q.s[k])²; +∞ between organs of different types.
double organ_distance(const Organ& a, const Organ& b, const FeatureScales& scales);

constexpr int kAzimuthBins = 8;

struct Planton {
  OrganType type = OrganType::Stem;
  size_t organ_count = 0;                 // |𝓛| in the samples
  std::vector<double> mean;               // 𝓖 in z coordinates
  std::vector<double> covariance;         // dim × dim, row-major, regularized (+ λI)
  double child_mean = 0.0, child_sd = 0.0;  // 𝓝 (child count of the organs in 𝓛)
  std::vector<std::vector<double>> exemplars;  // the organs' parameter vectors s (raw units)
};

// a[i, j]. p is conditioned on the parent's planton: p_ij = #edges i→j / #edges i→·.
struct Transition {
  double count = 0.0;                     // edges i → j in the samples
  double p = 0.0;
  double t_mean = 0.5, t_sd = 0.0;        // T: position on the parent
  double theta_mean = 0.0, theta_sd = 0.0;  // Ω: angle from the parent's tangent, radians
  std::array<double, kAzimuthBins> azimuth{};  // Ω: azimuth histogram over (−π, π], sums to 1
};

struct PlantonModel {
  FeatureScales scales;
  std::vector<Planton> plantons;
  std::vector<Transition> transitions;    // N × N, row-major [from * N + to]
  uint32_t root_planton = 0;
  double root_theta_mean = 0.0, root_theta_sd = 0.0;  // root stem's tilt from vertical
  double regularization = 1e-3;           // λ added to every covariance diagonal
  double damping = 1.0;                   // factor applied to child means (see damp_to_subcritical)
  size_t N() const { return plantons.size(); }
  const Transition& a(size_t i, size_t j) const { return transitions[i * plantons.size() + j]; }
  Transition& a(size_t i, size_t j) { return transitions[i * plantons.size() + j]; }
};

// Hard-assignment estimation (Wang 2006 §5.1.1, eqs. 3–4) from labelled samples pooled
// (Wang 2006 §5.2). labels[s][k] is the planton of organ k of sample s, all in [0, n_plantons); every
// planton must be used and hold organs of one type. Exemplars are left empty.
PlantonModel estimate_plantons(const std::vector<OrganTree>& samples,
                               const std::vector<std::vector<uint32_t>>& labels, size_t n_plantons,
                               const FeatureScales& scales, double regularization);

// Log-likelihood terms of eq. (5). Unary: log 𝓖(o.s) + log 𝓝(#children); −∞ for a planton
// of another type. Pair: log p_ij + log T(t) + log Ω(θ, φ), smoothed so that unseen
// transitions are unlikely but possible (labels can move).
struct OrganScores {
  std::vector<double> unary;  // M × N
};
OrganScores unary_scores(const PlantonModel& model, const OrganTree& tree);
double pair_score(const PlantonModel& model, uint32_t from, uint32_t to, const Organ& child);
double labelling_log_likelihood(const PlantonModel& model, const OrganTree& tree,
                                const std::vector<uint32_t>& labels);

// Tree max-product (Viterbi on the organ tree, log space): the labelling of one sample that
// maximizes eq. (5). Replaces the paper's chain DP (Algorithm 1 treats o_{k−1} as the parent
// of o_k), which is wrong for trees.
std::vector<uint32_t> relabel_max_product(const PlantonModel& model, const OrganTree& tree);

// E[max(0, round(X))] for X ~ 𝓝(mean, sd²): the expected child count synthesis draws.
double expected_children(double mean, double sd);
// Expected offspring matrix M_ij = E[n_i] p_ij (leaf plantons have no children).
std::vector<double> offspring_matrix(const PlantonModel& model);
double spectral_radius(const std::vector<double>& matrix, size_t n);
// m_i = 1 + E[n_i] Σ_j p_ij m_j: expected organs of a tree started at planton i (uncapped);
// empty when the model is supercritical (spectral radius ≥ 1).
std::vector<double> expected_organ_counts(const PlantonModel& model);
// Multiplies every child mean by the largest factor in (0, 1] that keeps the spectral
// radius ≤ target; sets model.damping. Returns the radius after damping.
double damp_to_subcritical(PlantonModel& model, double target = 0.98);

// Model file: JSON, written atomically (temporary file + rename), floats rounded to 7
// significant digits so that the same model gives the same bytes everywhere.
nlohmann::json model_to_json(const PlantonModel& model);
std::string model_to_text(const PlantonModel& model, const nlohmann::json& provenance);
void save_model(const PlantonModel& model, const nlohmann::json& provenance,
                const std::filesystem::path& path);
// Malformed or inconsistent file (syntax, missing key, wrong type, NaN, sizes, probabilities,
// supercritical) → InputError naming the file, the line and the key.
PlantonModel parse_model(const std::string& text, const std::string& name);
PlantonModel load_model(const std::filesystem::path& path);

}  // namespace forest
