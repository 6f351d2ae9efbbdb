// `forest learn`: plantons and transitions from sample trees (Wang 2006) into a model file.
#include <chrono>
#include <cstdio>

#include "engine/app/commands.h"
#include "generators/core/input_error.h"
#include "generators/methods/plantons/plantons_learn.h"
#include "generators/methods/plantons/plantons_samples.h"

namespace forest::app {

int run_learn(const LearnArgs& args) {
  int sources = int(!args.species.empty()) + int(!args.samples.empty()) + int(args.ground_truth);
  if (sources != 1) throw InputError("learn", 0, "", "give exactly one of --species FILES..., --samples FILE, --ground-truth");
  std::filesystem::path out = args.out;
  std::error_code ec;
  std::filesystem::path dir = out.parent_path().empty() ? "." : out.parent_path();
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(out.string(), 0, "--out", "folder does not exist: " + dir.string());
  const uint64_t seed = args.seed.value_or(1);
  auto start = std::chrono::steady_clock::now();

  std::vector<OrganTree> samples;
  nlohmann::json provenance;
  provenance["seed"] = seed;
  if (args.ground_truth) {
    samples = ground_truth_samples(args.trees.value_or(3), seed);
    provenance["samples"] = "ground truth (plantons_samples.h), " + std::to_string(samples.size()) + " trees";
  } else {
    std::vector<TreeGraph> graphs;
    if (!args.samples.empty()) {
      graphs = load_samples(args.samples);
      provenance["samples"] = std::filesystem::path(args.samples).filename().string();
    } else {
      std::vector<std::filesystem::path> files(args.species.begin(), args.species.end());
      graphs = species_samples(files, args.trees.value_or(1), seed);
      nlohmann::json names = nlohmann::json::array();
      for (const auto& f : files) names.push_back(f.filename().string());
      provenance["species"] = names;
      provenance["trees_per_species"] = args.trees.value_or(1);
    }
    for (const TreeGraph& g : graphs) samples.push_back(organs_from_graph(g));
  }
  auto sampled = std::chrono::steady_clock::now();

  LearnParams params;
  params.seed = seed;
  params.initial_plantons = {args.stem_plantons, args.leaf_plantons};
  params.e_max = args.e_max;
  LearnResult r = learn_plantons(samples, params);
  auto learned = std::chrono::steady_clock::now();
  provenance["plantons_after_kmeans"] = r.plantons_after_kmeans;
  provenance["em_iterations"] = r.iterations;
  provenance["converged"] = r.converged;
  provenance["e_max"] = args.e_max;
  save_model(r.model, provenance, out);

  size_t organs = 0;
  for (const OrganTree& t : samples) organs += t.organs.size();
  std::vector<double> m = expected_organ_counts(r.model);
  std::printf("wrote %s: %zu samples, %zu organs, %zu plantons after k-means, %zu after %d EM iterations%s, "
              "spectral radius %.3f%s, expected organs %.1f\n",
              out.c_str(), samples.size(), organs, r.plantons_after_kmeans, r.model.N(), r.iterations,
              r.converged ? "" : " (not converged)", r.spectral_radius,
              r.model.damping < 1.0 ? " (child counts damped)" : "", m.empty() ? 0.0 : m[r.model.root_planton]);
  std::printf("samples %.3f s, learning %.3f s\n", std::chrono::duration<double>(sampled - start).count(),
              std::chrono::duration<double>(learned - sampled).count());
  return 0;
}

}  // namespace forest::app
