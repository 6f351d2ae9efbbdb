// `forest gallery` on a small species folder: one labelled cell per preset, in name order,
// each showing its tree, rendered under the validation layer.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "engine/tools/gallery/gallery.h"
#include "generators/core/input_error.h"
#include "tests/common/test_files.h"
#include "tests/gpu/validated_gpu_test.h"

using namespace forest;
namespace fs = std::filesystem;

namespace {

const fs::path kSpecies = fs::path(FOREST_SOURCE_DIR) / "scenes" / "species";

class GalleryTest : public ValidatedGpuTest {
 protected:
  void SetUp() override {
    dir_ = test::fresh_temp_dir("forest_gallery");
    ValidatedGpuTest::SetUp();
  }
  void TearDown() override {
    ValidatedGpuTest::TearDown();
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

// Pixels of the cell's picture that differ clearly from the background at the same row
// (sky and ground are uniform along a row; the left edge of the cell is background).
size_t tree_pixels(const FrameImage& sheet, uint32_t x0, uint32_t y0, uint32_t size) {
  size_t n = 0;
  for (uint32_t y = y0; y < y0 + size; ++y) {
    const uint8_t* bg = sheet.pixel(x0 + 1, y);
    for (uint32_t x = x0 + size / 4; x < x0 + 3 * size / 4; ++x) {
      const uint8_t* p = sheet.pixel(x, y);
      int d = std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]);
      n += d > 40 ? 1 : 0;
    }
  }
  return n;
}

size_t bright_pixels(const FrameImage& sheet, uint32_t x0, uint32_t y0, uint32_t w, uint32_t h) {
  size_t n = 0;
  for (uint32_t y = y0; y < y0 + h; ++y)
    for (uint32_t x = x0; x < x0 + w; ++x) n += sheet.pixel(x, y)[0] > 150 ? 1 : 0;
  return n;
}

}  // namespace

TEST_F(GalleryTest, OneLabelledCellPerPresetInNameOrder) {
  fs::copy_file(kSpecies / "conifer.toml", dir_ / "b_conifer.toml");
  fs::copy_file(kSpecies / "broadleaf.toml", dir_ / "a_broadleaf.toml");
  std::ofstream(dir_ / "notes.txt") << "not a preset\n";
  std::vector<fs::path> presets = list_species_presets(dir_);
  ASSERT_EQ(presets.size(), 2u);
  EXPECT_EQ(presets[0].filename(), "a_broadleaf.toml");

  GalleryOptions options;
  options.size = 64;
  options.columns = 2;
  options.samples = 1;
  std::vector<GalleryEntry> entries;
  size_t calls = 0;
  FrameImage sheet = render_gallery(ctx_, presets, options, &entries, [&](size_t done, size_t total) {
    ++calls;
    EXPECT_EQ(done, calls);
    EXPECT_EQ(total, 4u);  // generate and render each
  });
  EXPECT_EQ(calls, 4u);
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].name, "a_broadleaf");
  EXPECT_EQ(entries[1].name, "b_conifer");
  EXPECT_EQ(entries[0].method, "lsystem");
  EXPECT_GT(entries[0].triangles, 1000u);
  EXPECT_GT(entries[1].leaves, 300u);

  const uint32_t gap = 4, band = gallery_label_band(64);
  EXPECT_EQ(sheet.width, 2 * 64 + 3 * gap);
  EXPECT_EQ(sheet.height, 64 + band + 2 * gap);
  for (uint32_t c = 0; c < 2; ++c) {
    uint32_t x0 = gap + c * (64 + gap);
    EXPECT_GT(tree_pixels(sheet, x0, gap, 64), 64u * 32u / 12u) << "cell " << c << " shows no tree";
    EXPECT_GT(bright_pixels(sheet, x0, gap + 64, 64, band), 20u) << "cell " << c << " has no label";
  }
  // The two labels say different things.
  size_t differ = 0;
  for (uint32_t y = gap + 64; y < gap + 64 + band; ++y)
    for (uint32_t x = 0; x < 64; ++x) differ += sheet.pixel(gap + x, y)[0] != sheet.pixel(2 * gap + 64 + x, y)[0];
  EXPECT_GT(differ, 20u);
}

TEST_F(GalleryTest, BadPresetOrEmptyFolderIsAnInputError) {
  EXPECT_THROW(list_species_presets(dir_), InputError);                  // no *.toml
  EXPECT_THROW(list_species_presets(dir_ / "missing"), InputError);
  std::ofstream(dir_ / "bad.toml") << "method = \"lsystem\"\niterations = nan\n";
  try {
    render_gallery(ctx_, list_species_presets(dir_), GalleryOptions{});
    ADD_FAILURE() << "no error for a bad preset";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:2: iterations"), std::string::npos) << e.what();
  }
}
