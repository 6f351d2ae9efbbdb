// Method `particle-flow` (Neubert 2012 ch3, after Neubert et al. 2007): >= 2 silhouette masks (+ attractor
// polylines: trunk and first-order branches drawn on each image) -> density volume by least
// squares -> particles seeded by density flow to the base, merging into branches -> graph
// -> pipe radii, leaves, mesh.
#pragma once
#include "generators/species/registry.h"

namespace forest {

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kParticleFlowMethod;

}  // namespace forest
