// Method `visual-hull` (Shlyakhter 2001): silhouette masks + camera poses ->
// visual hull -> skeleton from the hull's medial axis -> open L-system grown and pruned
// inside the hull -> leaves (dropped where they project onto background) -> mesh.
#pragma once
#include "generators/species/registry.h"

namespace forest {

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kVisualHullMethod;

}  // namespace forest
