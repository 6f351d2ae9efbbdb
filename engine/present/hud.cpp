#include "engine/present/hud.h"

#include <algorithm>
#include <cmath>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace forest {

namespace {

constexpr int kPadding = 4;      // font pixels around the text
constexpr int kLineHeight = 10;  // font pixels per line (glyphs are 7 tall, some descend 2)
constexpr uint8_t kBackground[3] = {18, 22, 26};
constexpr uint8_t kText[3] = {236, 238, 228};

struct GlyphVertex {  // stb_easy_font's vertex layout
  float x, y, z;
  uint8_t color[4];
};

int line_width(const std::string& line) {
  std::string copy = line;  // stb_easy_font takes char*
  return stb_easy_font_width(copy.data());
}

}  // namespace

void text_panel_size(const std::vector<std::string>& lines, uint32_t scale, uint32_t* width, uint32_t* height) {
  int w = 0;
  for (const std::string& l : lines) w = std::max(w, line_width(l));
  *width = lines.empty() ? 0 : uint32_t(w + 2 * kPadding) * scale;
  *height = lines.empty() ? 0 : uint32_t(int(lines.size()) * kLineHeight + 2 * kPadding) * scale;
}

OverlayImage draw_text_panel(const std::vector<std::string>& lines, uint32_t scale, bool bgra) {
  scale = std::max(scale, 1u);
  OverlayImage img;
  text_panel_size(lines, scale, &img.width, &img.height);
  img.bytes.resize(size_t(img.width) * img.height * 4);
  auto put = [&](size_t i, const uint8_t rgb[3]) {
    img.bytes[i + 0] = bgra ? rgb[2] : rgb[0];
    img.bytes[i + 1] = rgb[1];
    img.bytes[i + 2] = bgra ? rgb[0] : rgb[2];
    img.bytes[i + 3] = 255;
  };
  for (size_t i = 0; i < img.bytes.size(); i += 4) put(i, kBackground);

  std::vector<GlyphVertex> quads;
  for (size_t row = 0; row < lines.size(); ++row) {
    std::string text = lines[row];
    quads.resize(text.size() * 64 + 64);  // at most 16 quads (64 vertices) per character
    int n = stb_easy_font_print(float(kPadding), float(kPadding + int(row) * kLineHeight), text.data(), nullptr,
                                quads.data(), int(quads.size() * sizeof(GlyphVertex)));
    for (int q = 0; q < n; ++q) {  // every quad is an axis-aligned rectangle
      const GlyphVertex* v = &quads[size_t(q) * 4];
      float x0 = std::min({v[0].x, v[1].x, v[2].x, v[3].x}), x1 = std::max({v[0].x, v[1].x, v[2].x, v[3].x});
      float y0 = std::min({v[0].y, v[1].y, v[2].y, v[3].y}), y1 = std::max({v[0].y, v[1].y, v[2].y, v[3].y});
      int px0 = std::max(0, int(std::lround(x0 * float(scale))));
      int px1 = std::min(int(img.width), int(std::lround(x1 * float(scale))));
      int py0 = std::max(0, int(std::lround(y0 * float(scale))));
      int py1 = std::min(int(img.height), int(std::lround(y1 * float(scale))));
      for (int y = py0; y < py1; ++y)
        for (int x = px0; x < px1; ++x) put((size_t(y) * img.width + size_t(x)) * 4, kText);
    }
  }
  return img;
}

}  // namespace forest
