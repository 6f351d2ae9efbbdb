#include <cstdio>
#include <fstream>
#include <sstream>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "engine/present/image_io.h"
#include "generators/methods/magnetic/magnetic_method.h"
#include "generators/species/registry.h"

namespace forest::app {

namespace {

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot read file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

int run_generate(const GenerateArgs& args) {
  if (args.species.empty() && args.method.empty())
    throw InputError("generate", 0, "", "give --species FILE or --method ID");
  if (args.out.empty() && args.svg.empty()) throw InputError("generate", 0, "", "give --out MODEL.glb and/or --svg FILE.svg");
  GenerateOptions options;
  options.seed = args.seed;
  if (!args.out.empty()) check_output_path(args.out, "--out");
  if (!args.svg.empty()) check_output_path(args.svg, "--svg");

  // The species text once: the model and the SVG come from the same preset and seed.
  std::string text, name;
  if (!args.species.empty()) {
    text = read_text_file(args.species);
    name = args.species;
  } else {
    text = default_species_text(args.method);
    name = "builtin:" + args.method;
  }
  // Everything is computed before anything is written: a bad input leaves no file behind.
  std::string svg;
  if (!args.svg.empty()) svg = magnetic_svg_from_species_text(text, name, options.seed);
  TreeModel model;
  bool want_model = !args.out.empty();
  if (want_model) {
    // Paths inside a species file are relative to it.
    model = args.species.empty() ? generate_from_species_text(text, name, options)
                                 : generate_from_species(args.species, options);
    std::string method = model.meta.value("method", "");
    if (!args.method.empty() && args.method != method)
      throw InputError(args.species, 0, "method", "is '" + method + "' but --method " + args.method + " was given");
  }
  if (want_model) save_glb(model, args.out);
  if (!svg.empty()) {
    write_text_file(args.svg, svg);
    size_t curves = 0;
    for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++curves;
    std::printf("wrote %s: %zu curves\n", args.svg.c_str(), curves);
  }
  if (want_model) {
    size_t triangles = model.branches.indices.size() / 3;
    std::printf("wrote %s: %zu branch triangles, %zu leaves, height %.2f m, seed %llu\n", args.out.c_str(), triangles,
                model.leaves.size(), double(model.meta.value("height", 0.0)),
                (unsigned long long)model.meta.value("seed", uint64_t(0)));
  }
  return 0;
}

int run_make_inputs(const MakeInputsArgs& args) {
  make_inputs(args.out);
  for (const MethodEntry* m : method_table())
    if (m->make_inputs) std::printf("wrote %s/%s/\n", args.out.c_str(), m->id);
  return 0;
}

}  // namespace forest::app
