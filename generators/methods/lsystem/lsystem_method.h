// Method `lsystem` (Neubert 2012 ch2): a species file names an axiom, productions and turtle
// parameters; the skeleton is the turtle's drawing of the rewritten string, radii follow the
// pipe model, leaves come from L symbols or sit on the terminal twigs.
#pragma once
#include "generators/species/registry.h"

namespace forest {

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kLsystemMethod;

}  // namespace forest
