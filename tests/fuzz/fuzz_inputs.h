// One entry point per loader of untrusted input. Each runs the loader on raw bytes and
// returns normally when the loader either accepted the input or refused it with an
// InputError; any other exception, a crash, a sanitizer report or a hang is a bug.
// Shared by the libFuzzer targets (fuzz_main.cpp, one executable per entry) and by the
// unit test that replays the committed corpus and every past crash (unit.FuzzCorpus.*).
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

namespace forest::fuzz {

using Bytes = std::span<const uint8_t>;

void scene_input(Bytes bytes);    // engine/scene/scene_file: parse_scene_text
void species_input(Bytes bytes);  // generators/common/toml_reader: every typed accessor
void glb_input(Bytes bytes);      // generators/asset: decode_glb (bake data included)
void strokes_input(Bytes bytes);  // generators/methods/strokes_io: JSON (first byte even) or SVG
void mask_input(Bytes bytes);     // generators/methods/image_inputs: load_mask (OIIO)
void views_input(Bytes bytes);    // generators/methods/image_inputs: load_view_set

struct Target {
  std::string_view name;  // also the corpus folder: tests/fuzz/corpus/<name>/
  void (*run)(Bytes);
};
std::span<const Target> targets();

}  // namespace forest::fuzz
