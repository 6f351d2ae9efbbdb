#include <cstdio>

#include "engine/app/commands.h"
#include "generators/bake/asset_io.h"
#include "generators/common/input_error.h"
#include "generators/methods/methods.h"

namespace forest::app {

int run_generate(const GenerateArgs& args) {
  if (args.species.empty() && args.method.empty())
    throw InputError("generate", 0, "", "give --species FILE or --method ID");
  GenerateOptions options;
  options.seed = args.seed;
  std::filesystem::path out = args.out;
  std::error_code ec;
  std::filesystem::path dir = out.parent_path().empty() ? "." : out.parent_path();
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(out.string(), 0, "--out", "folder does not exist: " + dir.string());

  TreeModel model;
  if (!args.species.empty()) {
    model = generate_from_species(args.species, options);
    std::string method = model.meta.value("method", "");
    if (!args.method.empty() && args.method != method)
      throw InputError(args.species, 0, "method", "is '" + method + "' but --method " + args.method + " was given");
  } else {
    model = generate_from_species_text(default_species_text(args.method), "builtin:" + args.method, options);
  }
  save_glb(model, out);
  size_t triangles = model.branches.indices.size() / 3;
  std::printf("wrote %s: %zu branch triangles, %zu leaves, height %.2f m, seed %llu\n", out.c_str(), triangles,
              model.leaves.size(), double(model.meta.value("height", 0.0)),
              (unsigned long long)model.meta.value("seed", uint64_t(0)));
  return 0;
}

int run_make_inputs(const MakeInputsArgs& args) {
  make_inputs(args.out);
  for (const MethodEntry& m : method_table())
    if (m.make_inputs) std::printf("wrote %s/%s/\n", args.out.c_str(), m.id);
  return 0;
}

}  // namespace forest::app
