// The `forest` subcommands. Each returns the process exit code:
// 0 success, 2 bad input or usage, 1 internal failure (thrown, mapped in main).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "engine/render/pr_bake.h"

namespace forest::app {

struct BakeArgs;
struct BakeResult {
  PrMeasurement measurement;
  double hull_seconds = 0, pr_seconds = 0;
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
  std::string out;
};
int run_generate(const GenerateArgs& args);

struct MakeInputsArgs {
  std::string out;
};
int run_make_inputs(const MakeInputsArgs& args);

struct PreviewArgs {
  std::string model;
  std::string out;
  std::string device;
  uint32_t size = 384;
  uint32_t views = 4;
};
int run_preview(const PreviewArgs& args);

struct BakeArgs {
  std::string model;
  std::string out;            // empty: bake in place
  std::string priority = "combined";
  std::optional<uint64_t> seed;
  uint32_t views = 6;
  uint32_t resolution = 256;
  std::string device;
};
int run_bake(const BakeArgs& args);

struct ReportArgs {
  std::string model;
  std::string out;
};
int run_report(const ReportArgs& args);

struct RenderArgs {
  std::string scene;
  std::string out;
  std::string device;
  std::optional<uint32_t> width, height;
  bool stats = false;
  bool validate = false;
  std::string path;              // camera path name ([[path]] name)
  std::optional<uint32_t> frame; // frame of the path (time = frame / fps)
  std::optional<double> time;    // seconds along the path
  std::string cache;             // species cache folder (default: default_cache_dir())
};
int run_render(const RenderArgs& args);

}  // namespace forest::app
