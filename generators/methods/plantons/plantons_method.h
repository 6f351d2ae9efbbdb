// Method `plantons` (Wang 2006): trees synthesized from a two-level
// statistical model — plantons (clusters of similar organs) and the transitions between
// them — learned from sample trees by `forest learn` (plantons_learn.h). A preset names the
// learned model file; synthesis (plantons_synth.h) builds an organ tree that is turned into
// a TreeGraph and meshed like every other method.
#pragma once
#include "generators/species/registry.h"

namespace forest {

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kPlantonsMethod;

}  // namespace forest
