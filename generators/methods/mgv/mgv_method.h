// Method `mgv` (Xu 2015 ch5–6): species file -> MgvParams -> grow_mgv (mgv_grow.h) ->
// skeleton style (radii w = s^ζ or pipe model, leaves) -> the shared model stage.
#pragma once
#include <string>

#include "generators/core/toml_reader.h"
#include "generators/species/registry.h"
#include "generators/methods/mgv/mgv_grow.h"

namespace forest {

// Reads the method's keys (not the skeleton style); errors name file, line and key.
MgvParams read_mgv_params(const TomlTable& t);

// The method's registry entry (species keys, skeleton pass, built-in preset, inputs).
extern const MethodEntry kMgvMethod;

}  // namespace forest
