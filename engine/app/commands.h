// The `forest` subcommands. Each returns the process exit code:
// 0 success, 2 bad input or usage, 1 internal failure (thrown, mapped in main).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/tools/bake/pr_bake.h"

namespace forest::app {

struct BakeArgs;
struct BakeResult {
  PrMeasurement measurement;
  double hull_seconds = 0, pr_seconds = 0, impostor_seconds = 0;
  size_t hull_triangles = 0;
};
// Hull, priority order and PR tables into `model` (used by `bake` and `generate --bake`).
BakeResult bake_model(TreeModel& model, const BakeArgs& args);

struct InfoArgs {
  std::string device;
};
int run_info(const InfoArgs& args);

struct GenerateArgs {
  std::string species;
  std::string method;
  std::optional<uint64_t> seed;
  std::string out;  // .glb (may be empty when svg is given)
  std::string svg;  // magnetic only: the 2D curves as SVG
};
int run_generate(const GenerateArgs& args);

struct MakeInputsArgs {
  std::string out;
};
int run_make_inputs(const MakeInputsArgs& args);

struct LearnArgs {
  std::string out;
  std::optional<uint64_t> seed;
  std::vector<std::string> species;  // sample trees generated from these presets ...
  std::string samples;               // ... or read from a sample file ...
  bool ground_truth = false;         // ... or drawn from the synthetic ground truth
  std::optional<size_t> trees;       // trees per species / ground-truth trees
  int stem_plantons = 8;             // k-means k per organ type
  int leaf_plantons = 2;
  double e_max = 16.0;
};
int run_learn(const LearnArgs& args);

struct PreviewArgs {
  std::string model;
  std::string out;
  std::string device;
  uint32_t size = 384;
  uint32_t views = 4;
  bool bark_lods = false;  // one view per bark LOD level, leaves hidden
  bool impostor = false;   // a second row: the baked impostor from the same views
};
int run_preview(const PreviewArgs& args);

struct GalleryArgs {
  std::string out;
  std::string species_dir = "scenes/species";
  uint32_t size = 256;
  uint32_t columns = 0;  // 0: about square
  bool own_scale = false;  // each tree fills its cell (no common scale, no human figure)
  std::string device;
};
int run_gallery(const GalleryArgs& args);

struct BakeArgs {
  std::string model;
  std::string out;            // empty: bake in place
  std::string priority = "combined";
  std::optional<uint64_t> seed;
  uint32_t views = 6;
  uint32_t resolution = 512;  // projected size of the PR tables' size 0
  std::string device;
};
int run_bake(const BakeArgs& args);

struct ReportArgs {
  std::string model;
  std::string out;
};
int run_report(const ReportArgs& args);

struct MeasureArgs {
  std::string species;  // a preset: habit from its skeleton, coverage and depth from its model ...
  std::string model;    // ... or a .glb: coverage and depth only
  std::optional<uint64_t> seed;
  std::string json;   // also write the numbers here
  std::string masks;  // existing folder: the leaf masks as leaves_az<deg>.png
  uint32_t resolution = 512;
  std::string device;
  bool validate = false;
};
int run_measure(const MeasureArgs& args);

struct RenderArgs {
  std::string scene;
  std::string out;
  std::string device;
  std::optional<uint32_t> width, height;
  std::optional<bool> occlusion;  // --occlusion on|off, overrides [render].occlusion
  std::optional<bool> impostors;  // --impostors on|off, overrides [render].impostors
  std::optional<bool> shadows;    // --shadows on|off, overrides [render].shadows
  std::optional<glm::vec2> sun;   // --sun AZIMUTH,ELEVATION (degrees), overrides [sky].sun_direction
  std::optional<float> exposure;  // --exposure, overrides [render].exposure
  std::string mode;               // --mode full|cook|opt|target, overrides [render].mode
  std::optional<float> quality;   // --quality, overrides [render].quality (mode target)
  std::string view;               // --view shaded|lambda|mask, overrides [render].view
  std::string overlay;            // --overlay pyramid: the depth pyramid in the top-right quarter
  bool stats = false;
  bool validate = false;
  std::string path;              // camera path name ([[path]] name)
  std::optional<uint32_t> frame; // frame of the path (time = frame / fps)
  std::optional<double> time;    // seconds along the path
  std::string cache;             // species cache folder (default: default_cache_dir())
};
int run_render(const RenderArgs& args);

struct CompareArgs {
  std::string reference;
  std::string test;
  std::string diff;                   // Fig 7.1 picture (optional)
  uint8_t threshold = 128;            // coverage threshold on the brightest channel
  std::optional<double> min_quality;  // exit 3 when Q falls below it
};
// Exit 3 (not 1 or 2) when Q is under --min-quality, so scripts can tell a regression from
// a bad input.
int run_compare(const CompareArgs& args);
struct WalkArgs {
  std::string scene;
  std::string device;
  std::optional<uint32_t> width, height;  // render resolution (and first window size)
  std::optional<uint32_t> frames;         // scripted: quit after N frames, fixed 1/30 s steps
  std::string screenshot;                 // with --frames: the last frame; else the [C] key's file
  bool fly = false;                       // scripted camera move: forward while turning
  bool play = false;                      // start playing the scene's first camera path
  std::optional<uint32_t> resize_at;      // scripted window resize at this frame
  bool no_hud = false;
  bool validate = false;
  std::string present = "auto";  // auto | blit | pass (the copy pass, where blits are unsupported)
  std::optional<bool> shadows;   // --shadows on|off, overrides [render].shadows ([J] toggles)
  std::optional<bool> impostors;  // --impostors on|off, overrides [render].impostors ([I] toggles)
};
int run_walk(const WalkArgs& args);

struct BenchArgs {
  std::string scene;
  std::string path;                 // [[path]] name (default: the scene's first path)
  std::string modes = "full,cook,opt,opt-combined,opt-occl";
  uint32_t frames = 0;              // at most this many frames (0: the whole path)
  uint32_t every = 1;               // play every k-th frame of the path
  uint32_t pr_every = 10;           // P, R, Q at every k-th played frame (0: never)
  uint32_t tree_pr = 0;             // at PR frames, also Q of this many trees, each alone (0: none)
  std::optional<uint32_t> occlusion_warmup;  // frames drawn before each played one (default: all between)
  std::string shadows;              // on | off | on,off: every mode with each (default: [render].shadows)
  std::optional<bool> impostors;    // --impostors on|off: every mode with or without them (default: [render].impostors)
  uint32_t probe_instances = 64;    // throughput probe: sheets of 96 × 96 quads (0: no probe)
  std::optional<uint32_t> width, height;
  std::string out;                  // existing folder
  std::string device;
  std::string cache;
  bool validate = false;
};
int run_bench(const BenchArgs& args);

struct ExportArgs {
  std::string model;  // .glb asset
  std::string out;    // X.glb; LODs beside it as X_LOD1.glb ...
  bool flatten = false;
};
int run_export(const ExportArgs& args);

struct CacheArgs {
  std::string action;                // ls | verify | clear | build
  std::string cache;                 // folder (default: default_cache_dir())
  bool stale_only = false;           // clear --stale: only entries verify would name
  std::vector<std::string> presets;  // build: species presets
  std::string scene;                 // build: a scene's [[species]] with its [bake]
  uint32_t jobs = 1;                 // build: bakes at once, each on its own device context
  std::string shard;                 // build: "i/n", every n-th spec from the i-th
  std::optional<std::string> priority;  // build: [bake] settings for presets
  std::optional<uint32_t> views, resolution;
  bool no_impostor = false;
  std::string device;
  bool validate = false;
};
// verify exits 1 when an entry is stale or corrupt.
int run_cache(const CacheArgs& args);
int run_cache_build(const CacheArgs& args);

}  // namespace forest::app
