// Limits on counts that user input controls (generators/core/limits.h): each absurd count
// is one InputError naming file and key, raised before the memory is allocated. Vulkan
// failures name their VkResult.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "engine/scene/scene_file.h"
#include "engine/vk/context.h"
#include "generators/asset/asset_io.h"
#include "generators/core/input_error.h"
#include "generators/core/limits.h"
#include "generators/methods/common/image_inputs.h"
#include "generators/species/registry.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

const char* kSmallSpecies = R"(method = "lsystem"
iterations = 2
axiom = "X"
angle = 25.0
step = 0.3
shoots_per_tip = 2
leaf_size = 0.2
[[production]]
predecessor = "X"
successor = "F[[X]-X]F[+FX]-X"
)";

template <class Fn>
std::string input_error(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Rewrites the JSON chunk of a .glb (the BIN chunk is kept).
std::vector<uint8_t> edit_glb_json(const std::vector<uint8_t>& glb, const std::function<void(nlohmann::json&)>& edit) {
  auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  size_t json_len = u32(12);
  nlohmann::json j = nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + std::ptrdiff_t(json_len));
  edit(j);
  std::string text = j.dump();
  while (text.size() % 4) text.push_back(' ');
  std::vector<uint8_t> bin(glb.begin() + 20 + std::ptrdiff_t(json_len), glb.end());  // BIN chunk with its header
  std::vector<uint8_t> out;
  auto put = [&](uint32_t v) {
    uint8_t b[4];
    std::memcpy(b, &v, 4);
    out.insert(out.end(), b, b + 4);
  };
  put(0x46546C67u);
  put(2);
  put(uint32_t(20 + text.size() + bin.size()));
  put(uint32_t(text.size()));
  put(0x4E4F534Au);
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

std::string scene_with_species(int species, const std::string& extra) {
  std::string s = "[render]\nwidth = 64\nheight = 48\n";
  for (int i = 0; i < species; ++i) s += "[[species]]\npreset = \"species/broadleaf.toml\"\n";
  return s + extra;
}

}  // namespace

TEST(Limits, AbsurdLeafCountInGlbRefusedBeforeReading) {
  std::vector<uint8_t> good = encode_glb(generate_from_species_text(kSmallSpecies, "small.toml"));
  std::vector<uint8_t> bad = edit_glb_json(good, [](nlohmann::json& j) {
    for (auto& node : j["nodes"])
      if (node.value("name", "") == "leaves") {
        int a = node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"];
        j["accessors"][size_t(a)]["count"] = 10'000'000;  // 10^7 leaves claimed, none stored
      }
  });
  std::string e = input_error([&] { decode_glb(bad, "huge.glb"); });
  EXPECT_TRUE(has(e, "huge.glb") && has(e, "10000000 leaves") && has(e, std::to_string(kMaxLeavesPerModel))) << e;
  EXPECT_NO_THROW(decode_glb(edit_glb_json(good, [](nlohmann::json&) {}), "same.glb"));  // the editing is sound
}

TEST(Limits, GlbMetadataOfTheWrongTypeIsAnInputError) {
  std::vector<uint8_t> good = encode_glb(generate_from_species_text(kSmallSpecies, "small.toml"));
  auto with_meta = [&](const char* key, nlohmann::json value) {
    return edit_glb_json(good, [&](nlohmann::json& j) { j["extras"]["forest"][key] = value; });
  };
  EXPECT_TRUE(has(input_error([&] { decode_glb(with_meta("species", 3), "m.glb"); }), "extras.forest.species"));
  EXPECT_TRUE(has(input_error([&] { decode_glb(with_meta("seed", "x"), "m.glb"); }), "extras.forest.seed"));
  EXPECT_TRUE(has(input_error([&] { decode_glb(with_meta("seed", -4), "m.glb"); }), "extras.forest.seed"));
  // Bounding sphere beyond float range: recomputed from the geometry, never narrowed.
  TreeModel m = decode_glb(with_meta("bounding_sphere", {1e300, 0, 0, 1}), "m.glb");
  EXPECT_LT(std::abs(m.bounding_sphere.x), 1e3f);
}

TEST(Limits, SceneTreeAndSpeciesCounts) {
  const fs::path base = fs::path(FOREST_SOURCE_DIR) / "scenes";
  std::string e = input_error([&] {
    parse_scene_text(scene_with_species(1, "[placement]\ncount = 100000000\n"), "big.toml", base);
  });
  EXPECT_TRUE(has(e, "big.toml:7:") && has(e, "placement.count")) << e;
  std::string trees = "[placement]\ncount = " + std::to_string(kMaxTreeInstances) + "\n[[tree]]\nx = 0\nz = 0\n";
  e = input_error([&] { parse_scene_text(scene_with_species(1, trees), "big.toml", base); });
  EXPECT_TRUE(has(e, "big.toml") && has(e, "tree") && has(e, "limit")) << e;
  e = input_error([&] { parse_scene_text(scene_with_species(int(kMaxSceneSpecies) + 1, ""), "many.toml", base); });
  EXPECT_TRUE(has(e, "many.toml:4:") && has(e, "species") && has(e, "257")) << e;
  EXPECT_NO_THROW(parse_scene_text(scene_with_species(2, "[placement]\ncount = 1000000\n"), "ok.toml", base));
}

TEST(Limits, HugeMaskHeaderRefusedBeforeDecoding) {
  // A PNG whose header claims 65536 x 65536 pixels (16 GiB as float RGBA) and holds none.
  const fs::path file = fs::temp_directory_path() / ("forest_limits_" + std::to_string(getpid()) + ".png");
  const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',
                               0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 1, 0, 0, 0, 1, 0, 0, 8, 6, 0, 0, 0,
                               0x00, 0x00, 0x00, 0x00,  // CRC (wrong on purpose: either check refuses it)
                               0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof(png));
  std::string e = input_error([&] { load_mask(file); });
  EXPECT_TRUE(has(e, file.string())) << e;
  fs::remove(file);
  // Not PNG or OpenEXR: refused by signature, whatever OpenImageIO could read.
  const fs::path bmp = fs::temp_directory_path() / ("forest_limits_" + std::to_string(getpid()) + ".bmp");
  std::ofstream(bmp, std::ios::binary) << "BM this is no mask";
  e = input_error([&] { load_mask(bmp); });
  EXPECT_TRUE(has(e, "not a PNG or OpenEXR")) << e;
  fs::remove(bmp);
}

TEST(Limits, VulkanFailuresNameTheResult) {
  auto message = [](VkResult r) {
    try {
      vk::check(r, "vkQueueSubmit2(queue)");
    } catch (const vk::VkFailure& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NO_THROW(vk::check(VK_SUCCESS, "x"));
  std::string lost = message(VK_ERROR_DEVICE_LOST);
  EXPECT_TRUE(has(lost, "VK_ERROR_DEVICE_LOST") && has(lost, "device was lost") && has(lost, "vkQueueSubmit2(queue)"))
      << lost;
  std::string oom = message(VK_ERROR_OUT_OF_DEVICE_MEMORY);
  EXPECT_TRUE(has(oom, "VK_ERROR_OUT_OF_DEVICE_MEMORY") && has(oom, "out of GPU memory")) << oom;
  EXPECT_FALSE(has(oom, "\n"));
}
