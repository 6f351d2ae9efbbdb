// The HUD of `forest walk`: a few lines of text on a small opaque panel, composited on the
// CPU. Glyphs come from stb_easy_font (Debian libstb-dev), which builds every character from
// axis-aligned quads; we fill those rectangles. Cost is O(text), independent of the scene.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace forest {

// A small picture in a swapchain's byte order, copied 1:1 over the frame's top-left corner.
struct OverlayImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> bytes;  // 4 per pixel, top row first
};

// Light text on a dark panel; `scale` multiplies the 1-pixel strokes of the font (1 at
// 720p, 2 on bigger windows). `bgra`: write B, G, R, A instead of R, G, B, A. Characters
// outside printable ASCII draw nothing.
OverlayImage draw_text_panel(const std::vector<std::string>& lines, uint32_t scale, bool bgra);

// The panel size draw_text_panel() gives, without drawing (for buffer sizing).
void text_panel_size(const std::vector<std::string>& lines, uint32_t scale, uint32_t* width, uint32_t* height);

}  // namespace forest
