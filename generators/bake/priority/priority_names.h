// The leaf orders of the bake by name (extras.forest.priority, forest bake --priority): the
// enum and its names alone, so that the asset reader can check a name without the bake.
#pragma once
#include <optional>
#include <string_view>

namespace forest {

enum class Priority {
  random,       // Cook et al. 2007: a seeded shuffle, uncorrelated with anything
  density,      // Neubert 2012 §7.3.2: leaves in dense regions (high F) go first; random once uniform
  orientation,  // Neubert 2012 §7.3.3: small angle α between leaf and hull normal survives longer
  combined,     // Neubert 2012 §7.3.4: P = P_silhouette² + P_density, normalized, jittered, descending
  // Ours, from Neubert 2012 §7.3's findings (density helps at high λ, orientation at small λ) taken as a
  // switch instead of a blend: the leaves density's greedy phase removes go first, in that
  // order; the survivors are kept by orientation (small α last to go).
  layered,
};

std::string_view priority_name(Priority p);
std::optional<Priority> parse_priority(std::string_view name);  // nullopt for unknown names

}  // namespace forest
