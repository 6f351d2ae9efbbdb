#include <cstdio>
#include <filesystem>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/present/image_io.h"
#include "engine/tools/measure/tree_measure.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/tree/habit_ranges.h"
#include "generators/species/registry.h"

namespace forest::app {

int run_measure(const MeasureArgs& args) {
  if (args.species.empty() == args.model.empty())
    throw InputError("measure", 0, "", "give one of --species FILE.toml or --model FILE.glb");
  if (!args.model.empty() && args.seed) throw InputError("measure", 0, "--seed", "applies to --species only");
  if (!args.json.empty()) check_output_path(args.json, "--json");
  if (!args.masks.empty() && !std::filesystem::is_directory(args.masks))
    throw InputError(args.masks, 0, "--masks", "is not an existing folder");
  // Generation and every bad input come before the GPU is touched.
  TreeGraph graph;
  TreeModel model = args.species.empty() ? load_glb(args.model)
                                         : generate_from_species(args.species, GenerateOptions{args.seed, &graph});
  CommandContext context(context_options(args.device, args.validate));
  LeafCoverageOptions coverage;
  coverage.resolution = args.resolution;
  coverage.keep_masks = !args.masks.empty();
  TreeMeasurement m = measure_tree(context.ctx, model, args.species.empty() ? nullptr : &graph, coverage);
  if (!args.species.empty()) m.ranges = read_habit_ranges(TomlDocument::load(args.species).root());
  if (validation_failed(context.ctx, "measurement")) return 1;
  for (const std::string& line : measurement_lines(m)) std::printf("%s\n", line.c_str());
  nlohmann::json json = measurement_json(m);
  json["source"] = args.species.empty() ? args.model : args.species;
  json["seed"] = model.meta.value("seed", uint64_t(0));
  if (!args.json.empty()) write_text_file(args.json, json.dump(2) + "\n");
  for (size_t i = 0; i < m.coverage.masks.size(); ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "leaves_az%03.0f.png", m.coverage.views[i].azimuth_deg);
    write_image(m.coverage.masks[i], std::filesystem::path(args.masks) / name);
  }
  return 0;
}

}  // namespace forest::app
