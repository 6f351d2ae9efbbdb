// A small L-system preset (a few hundred leaves, a few LOD levels): the model the asset
// tests encode, decode and export.
#pragma once

namespace forest::test {

inline const char* kSmallSpecies = R"(method = "lsystem"
iterations = 3
axiom = "X"
angle = 25.0
angle_jitter = 5.0
roll_jitter = 180.0
step = 0.3
step_jitter = 0.2
shoots_per_tip = 2
leaf_size = 0.2
bark_color = [0.3, 0.2, 0.1]
leaf_color = [0.1, 0.4, 0.05]
[[production]]
predecessor = "X"
successor = "F[[X]-X]F[+FX]-X"
[[production]]
predecessor = "F"
successor = "FF"
)";

}  // namespace forest::test
