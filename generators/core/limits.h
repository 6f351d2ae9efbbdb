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
// Frames ([render] width/height, --width/--height) and images read from files.
inline constexpr uint32_t kMinFrameSide = 16;
inline constexpr uint32_t kMaxFrameSide = 8192;
inline constexpr uint32_t kMaxShadowResolution = 4096;  // texels per side of one shadow cascade
inline constexpr int kMaxImageSide = 8192;       // input masks and heightmaps, per side
inline constexpr int kMaxGlbImageSide = 4096;    // a texture inside a .glb, per side
inline constexpr uint32_t kMinBakeResolution = 32;    // pixels of a PR coverage render or preview view
inline constexpr uint32_t kMaxBakeResolution = 4096;
// [bake] resolution, bake --resolution: the PR tables' largest projected size (px across the
// bounding sphere); the coverage references of a bake hold 2 × views renders of about its square.
inline constexpr uint32_t kMaxPrSize0 = 2048;
inline constexpr uint32_t kMaxProbeInstances = 4096;  // forest bench --probe-instances
inline constexpr size_t kMaxHullSamples = 65536;      // extras.forest.hull_samples of one model

// Generators: what one preset or input file may ask for.
inline constexpr int64_t kMaxLSystemIterations = 12;
inline constexpr size_t kMaxLSystemSymbols = 2'000'000;
inline constexpr int64_t kMaxMgvNodes = 2'000'000;
inline constexpr int64_t kMaxMgvEndpoints = 200'000;
inline constexpr double kMaxMigGraphNodes = 4e6;  // all graphs of one tree together
inline constexpr double kMaxMigEndpoints = 200'000;
inline constexpr size_t kMaxPoissonCells = size_t(1) << 26;  // Poisson-disc grid cells
inline constexpr size_t kMaxYaoCells = size_t(1) << 25;      // Yao-graph bucket cells
inline constexpr double kMaxDrawingCoordinate = 1e4;  // strokes, |x| in drawing units
inline constexpr size_t kMaxStrokePoints = 100'000;
inline constexpr int kMaxSketchChildren = 7;  // 7! = 5040 label hypotheses at one sketch node
inline constexpr size_t kMaxPlantons = 10'000;
inline constexpr size_t kMaxPlantonExemplars = 2'000'000;
inline constexpr size_t kMaxSampleNodes = 4'000'000;  // nodes of all sample trees of `forest learn`
inline constexpr double kMaxHullBucketCells = 4.0e6;   // metaball hull field buckets
inline constexpr double kMaxHullGridPoints = 64.0e6;   // metaball hull marching-cubes grid

// Entries of the renderer's tail leaf buffer (64 MiB): the leaves of partly hidden trees
// that the per-leaf occlusion test keeps; forest5000 needs about 3 M.
inline constexpr uint32_t kMaxTailLeaves = 1u << 24;

}  // namespace forest
