// Hard limits on the counts that user input controls, and the memory each one allows. An
// input beyond a limit is an InputError (exit code 2, one line naming file and key), checked
// before the memory is allocated, so absurd numbers never end in an out-of-memory crash.
//
// Memory budget of the largest accepted inputs (sizes from shaders/gpu_types.h):
//   leaves per model   1 M   x 48 B (gpu::Leaf)            =  48 MB GPU, ~60 MB CPU
//   leaves per scene  16 M   x 48 B                        = 768 MB GPU (one leaf buffer)
//   tree instances     1 M   x (32 B instance + 2 x 32 B indirect commands) =  96 MB GPU
//   species per scene  256   x 128^2 RGBA8 leaf texture + mips            =  22 MB GPU
//   masks         8192^2 px  x 4 B (one float channel read)              = 256 MB CPU
//   glb textures  4096^2 px  x 4 B (RGBA8)                                =  64 MB CPU
//   frames        8192^2 px  x (color + depth + resolve, MSAA x8)          ~ 4.5 GB GPU at the
//                 extreme; the default 1280 x 720 x 4 needs ~60 MB.
#pragma once
#include <cstddef>
#include <cstdint>

namespace forest {

inline constexpr size_t kMaxLeavesPerModel = 1'000'000;
inline constexpr size_t kMaxSceneLeaves = 16'000'000;
inline constexpr uint32_t kMaxTreeInstances = 1'000'000;
inline constexpr uint32_t kMaxSceneSpecies = 256;  // leaf texture array layers (Vulkan minimum limit 256)
// Entries of the renderer's tail leaf buffer (64 MiB): the leaves of partly hidden trees
// that the per-leaf occlusion test keeps; forest5000 needs about 3 M.
inline constexpr uint32_t kMaxTailLeaves = 1u << 24;

}  // namespace forest
