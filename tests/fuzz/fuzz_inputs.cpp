#include "tests/fuzz/fuzz_inputs.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "engine/scene/scene_file.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/toml_reader.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/methods/common/strokes_io.h"

namespace forest::fuzz {

namespace fs = std::filesystem;

namespace {

std::string text_of(Bytes bytes) { return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()); }

// Runs `f`; an InputError is the loader's correct answer to bad input and is swallowed.
template <class F>
void refuse_or_accept(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  }
}

// A private scratch folder for loaders that take paths (removed at exit).
const fs::path& scratch_dir() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("forest-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(fs::temp_directory_path() / ("forest-fuzz-" + std::to_string(::getpid())), ec);
    });
    return d;
  }();
  return dir;
}

void write_bytes(const fs::path& file, Bytes bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out) throw std::runtime_error("fuzz harness: cannot write " + file.string());
}

// Walks every value of a table through the typed accessors a species reader uses.
void walk(const TomlTable& t, int depth) {
  if (depth > 8) return;
  for (auto&& [key, node] : t.raw()) {
    std::string_view k = key.str();
    refuse_or_accept([&] { t.number(k, -1e9, 1e9); });
    refuse_or_accept([&] { t.integer(k, -1'000'000'000, 1'000'000'000); });
    refuse_or_accept([&] { t.boolean(k, false); });
    refuse_or_accept([&] { t.string(k); });
    refuse_or_accept([&] { t.choice(k, "a", {"a", "b"}); });
    refuse_or_accept([&] { t.vec3(k, -1e6, 1e6); });
    refuse_or_accept([&] {
      if (auto sub = t.table(k)) walk(*sub, depth + 1);
    });
    refuse_or_accept([&] {
      for (const TomlTable& sub : t.tables(k)) walk(sub, depth + 1);
    });
    (void)node;
  }
  refuse_or_accept([&] { t.check_keys({"method", "seed", "name"}); });
  refuse_or_accept([&] { t.fail("key", "message"); });
}

}  // namespace

void scene_input(Bytes bytes) {
  // Relative preset/model paths resolve against a folder that does not exist.
  refuse_or_accept([&] { parse_scene_text(text_of(bytes), "fuzz.toml", "/nonexistent-forest-fuzz"); });
}

void species_input(Bytes bytes) {
  refuse_or_accept([&] {
    TomlDocument doc = TomlDocument::parse(text_of(bytes), "fuzz.toml");
    walk(doc.root(), 0);
  });
}

void glb_input(Bytes bytes) {
  refuse_or_accept([&] {
    TreeModel model = decode_glb(bytes, "fuzz.glb");  // bake data (extras.forest) validated here
    // What we accept we must be able to write and read back.
    std::vector<uint8_t> again = encode_glb(model);
    try {
      TreeModel back = decode_glb(again, "fuzz-roundtrip.glb");
      // (Leaves without a drawable card are dropped on purpose by the encoder.)
      bool leaves_kept = model.leaf_card.indices.empty() || back.leaves.size() == model.leaves.size();
      if (!leaves_kept || back.branches.indices.size() != model.branches.indices.size())
        throw std::logic_error("glb round trip changed the model");
      const BakeData &a = model.bake, &b = back.bake;
      if (a.hull.has_value() != b.hull.has_value() || (a.hull && a.hull->points != b.hull->points) ||
          a.priority != b.priority || a.baked() != b.baked() || a.pr_samples.size() != b.pr_samples.size() ||
          (a.pr_tables && (a.pr_tables->size0 != b.pr_tables->size0 || a.pr_tables->sizes.back().s_opt != b.pr_tables->sizes.back().s_opt)))
        throw std::logic_error("glb round trip changed the bake data");
    } catch (const InputError& e) {
      throw std::logic_error(std::string("an accepted .glb does not round-trip: ") + e.what());
    }
  });
}

void strokes_input(Bytes bytes) {
  const std::string text = text_of(bytes);
  for (bool svg : {false, true}) {
    refuse_or_accept([&] {
      Drawing d = svg ? parse_drawing_svg(text, "fuzz.svg") : parse_drawing_json(text, "fuzz.json");
      stroke_parents(d);
      strokes_with_role(d, "branch");
      try {
        Drawing back = parse_drawing_json(drawing_to_json(d), "fuzz-roundtrip.json");
        if (back.strokes.size() != d.strokes.size()) throw std::logic_error("stroke round trip changed the drawing");
        parse_drawing_svg(drawing_to_svg(d), "fuzz-roundtrip.svg");
      } catch (const InputError& e) {
        throw std::logic_error(std::string("an accepted drawing does not round-trip: ") + e.what());
      }
    });
  }
}

void mask_input(Bytes bytes) {
  const fs::path file = scratch_dir() / "mask.png";
  write_bytes(file, bytes);
  refuse_or_accept([&] { load_mask(file); });
}

void views_input(Bytes bytes) {
  // The views refer to masks view0.png ... view7.png: 8 copies of one committed 128x128 mask (the visual-hull cone).
  static const bool masks_ready = [] {
    const fs::path src = fs::path(FOREST_SOURCE_DIR) / "tests/fuzz/corpus/mask/view0.png";
    for (int i = 0; i < 8; ++i)
      fs::copy_file(src, scratch_dir() / ("view" + std::to_string(i) + ".png"), fs::copy_options::overwrite_existing);
    return true;
  }();
  (void)masks_ready;
  const fs::path file = scratch_dir() / "views.json";
  write_bytes(file, bytes);
  refuse_or_accept([&] { load_view_set(file); });
}

std::span<const Target> targets() {
  static const Target kTargets[] = {
      {"scene", scene_input}, {"species", species_input}, {"glb", glb_input},
      {"strokes", strokes_input}, {"mask", mask_input}, {"views", views_input},
  };
  return kTargets;
}

}  // namespace forest::fuzz
