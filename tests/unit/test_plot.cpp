// Plots written as PNG (plot.cpp): what a bench or report figure must keep readable.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "engine/present/image_io.h"
#include "engine/tools/report/plot.h"

using namespace forest;

namespace {

// Dark pixels (text, lines) in columns [x0, x1) of rows [y0, y1).
int dark_pixels(const FrameImage& image, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) {
  int n = 0;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) n += image.pixel(x, y)[0] < 128;
  return n;
}

// `plot` as write_plot draws it, read back from a PNG in a folder of its own.
FrameImage written(const Plot& plot, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("forest_test_plot_" + name);
  std::filesystem::create_directories(dir);
  write_plot(plot, dir / "plot.png");
  FrameImage image = read_image(dir / "plot.png");
  std::filesystem::remove_all(dir);
  return image;
}

}  // namespace

// A title is drawn at 20 px when it fits, smaller when it does not, and cut (whole UTF-8
// characters, "..." at the end) when even 12 px is too wide: it ends inside the figure
// instead of running off its right edge (device names and scene paths of bench titles).
TEST(Plot, LongTitlesShrinkThenAreCut) {
  FittedText short_title = fit_text("frame time", 20, 400);
  EXPECT_EQ(short_title.text, "frame time");
  EXPECT_EQ(short_title.size, 20);

  std::string longer = "GPU frame time (llvmpipe (LLVM 15.0.6, 256 bits), 640x360, forest5000.toml)";
  FittedText shrunk = fit_text(longer, 20, 520);
  EXPECT_EQ(shrunk.text, longer);
  EXPECT_LT(shrunk.size, 20);
  EXPECT_GE(shrunk.size, 12);

  std::string very_long;
  for (int i = 0; i < 40; ++i) very_long += "λ triangles ";
  FittedText cut = fit_text(very_long, 20, 300);
  EXPECT_EQ(cut.size, 12);
  ASSERT_GT(cut.text.size(), 3u);
  EXPECT_EQ(cut.text.substr(cut.text.size() - 3), "...");
  EXPECT_EQ(very_long.compare(0, cut.text.size() - 3, cut.text, 0, cut.text.size() - 3), 0) << "a prefix of the title";
  for (size_t i = 0; i + 3 < cut.text.size(); ++i) {  // no λ (2 bytes) split before the dots
    if ((uint8_t(cut.text[i]) & 0xE0) == 0xC0) {
      EXPECT_EQ(uint8_t(cut.text[i + 1]) & 0xC0, 0x80) << i;
    }
  }
}

// write_plot draws the fitted title: something in the title row, nothing at the right edge.
TEST(Plot, WritePlotDrawsTheTitleInsideTheFigure) {
  Plot plot;
  plot.width = 500;
  plot.height = 300;
  plot.series.push_back({"a", {{0.0f, 0.0f}, {1.0f, 1.0f}}});
  for (int i = 0; i < 60; ++i) plot.title += "tree triangles ";
  FrameImage image = written(plot, "long");
  ASSERT_EQ(image.width, 500u);
  EXPECT_GT(dark_pixels(image, 80, 200, 0, 40), 0) << "no title drawn";
  EXPECT_EQ(dark_pixels(image, 494, 500, 0, 40), 0) << "the title runs off the right edge";
  int inked_rows = 0;  // 12 px text spans about 12 rows ("g" included), 20 px text about 19
  for (uint32_t y = 0; y < 44; ++y) inked_rows += dark_pixels(image, 80, 500, y, y + 1) > 0;
  EXPECT_LE(inked_rows, 14) << "the title was not drawn at its fitted size";
}

// The y label (top left, starting left of the axes) and the title share no row: a long
// y label once ran into the title's first letters (saved.png, "saved (%)").
TEST(Plot, TitleAndYLabelDoNotOverlap) {
  Plot plot;
  plot.width = 600;
  plot.height = 300;
  plot.series.push_back({"a", {{0.0f, 0.0f}, {1.0f, 1.0f}}});
  plot.title = "leaves saved against Cook per frame";
  plot.y_label = "saved (%) and more";
  FrameImage image = written(plot, "label");
  int title_last = -1, label_first = -1;
  for (uint32_t y = 0; y < 48; ++y) {
    if (dark_pixels(image, 200, 500, y, y + 1) > 0) title_last = int(y);  // the title alone
    if (label_first < 0 && dark_pixels(image, 8, 70, y, y + 1) > 0) label_first = int(y);  // the label alone
  }
  ASSERT_GE(title_last, 0) << "no title drawn";
  ASSERT_GE(label_first, 0) << "no y label drawn";
  EXPECT_LT(title_last, label_first);
}
