#include "generators/methods/methods.h"

#include "generators/common/toml_reader.h"
#include "generators/methods/lsystem_method.h"

namespace forest {

namespace {

TreeModel generate(const TomlDocument& doc, const std::string& species_name,
                   const GenerateOptions& options) {
  TomlTable root = doc.root();
  std::string method = root.string("method");
  // `method` comes first so a reader (and the error for a wrong one) sees the method at once.
  int method_line = root.line_of("method");
  for (auto&& [key, value] : root.raw())
    if (int(key.source().begin.line) < method_line)
      throw InputError(doc.name(), int(key.source().begin.line), std::string(key.str()),
                       "`method` must be the first key of a species file");
  if (method == "lsystem") return generate_lsystem(root, species_name, options);
  std::string known;
  for (const std::string& id : method_ids()) known += (known.empty() ? "" : ", ") + id;
  root.fail("method", "unknown method '" + method + "' (known: " + known + ")");
}

}  // namespace

TreeModel generate_from_species(const std::filesystem::path& species_file,
                                const GenerateOptions& options) {
  TomlDocument doc = TomlDocument::load(species_file);
  return generate(doc, species_file.stem().string(), options);
}

TreeModel generate_from_species_text(const std::string& text, const std::string& name,
                                     const GenerateOptions& options) {
  TomlDocument doc = TomlDocument::parse(text, name);
  return generate(doc, std::filesystem::path(name).stem().string(), options);
}

std::vector<std::string> method_ids() { return {"lsystem"}; }

std::string default_species_text(const std::string& method) {
  if (method == "lsystem") return lsystem_default_species_text();
  std::string known;
  for (const std::string& id : method_ids()) known += (known.empty() ? "" : ", ") + id;
  throw InputError("", 0, "--method", "unknown method '" + method + "' (known: " + known + ")");
}

}  // namespace forest
