#include "engine/tools/report/plot.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "generators/core/input_error.h"

namespace forest {

namespace {
constexpr const char* kFont = "DejaVuSans";

std::string tick_label(float v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), std::abs(v) >= 100 || v == std::floor(v) ? "%.0f" : "%.2g", double(v));
  return buf;
}
}  // namespace

FittedText fit_text(std::string text, int size, int width) {
  auto fits = [&](const std::string& t, int sz) {
    OIIO::ROI r = OIIO::ImageBufAlgo::text_size(t, sz, kFont);
    return !r.defined() || r.width() <= width;  // undefined: no font, nothing is drawn anyway
  };
  for (; size > 12; --size)
    if (fits(text, size)) return {text, size};
  while (text.size() > 3 && !fits(text, size)) {
    text.resize(text.size() - 4);
    while (!text.empty() && (text.back() & 0xC0) == 0x80) text.pop_back();  // whole UTF-8 characters
    if (!text.empty() && (text.back() & 0x80)) text.pop_back();
    text += "...";
  }
  return {text, size};
}

glm::vec2 padded_range(const std::vector<PlotSeries>& series, int axis, float pad) {
  float lo = 1e30f, hi = -1e30f;
  for (const PlotSeries& s : series)
    for (glm::vec2 p : s.points)
      if (std::isfinite(p[axis])) lo = std::min(lo, p[axis]), hi = std::max(hi, p[axis]);
  if (lo > hi) return {0, 1};
  if (hi - lo < 1e-6f) hi = lo + 1.0f;
  float m = (hi - lo) * pad;
  return {lo - m, hi + m};
}

void write_plot(const Plot& plot, const std::filesystem::path& path) {
  OIIO::ImageBuf img(OIIO::ImageSpec(plot.width, plot.height, 3, OIIO::TypeDesc::UINT8), OIIO::InitializePixels::Yes);
  const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, grid[3] = {0.88f, 0.88f, 0.88f};
  OIIO::ImageBufAlgo::fill(img, white);
  const int left = 80, right = 24 + 170, top = 48, bottom = 64;  // legend on the right
  int x0 = left, x1 = plot.width - right, y0 = top, y1 = plot.height - bottom;
  auto px = [&](float x) { return x0 + int(std::lround((x - plot.x_range.x) / (plot.x_range.y - plot.x_range.x) * float(x1 - x0))); };
  auto py = [&](float y) { return y1 - int(std::lround((y - plot.y_range.x) / (plot.y_range.y - plot.y_range.x) * float(y1 - y0))); };

  for (int i = 0; i <= 5; ++i) {  // grid and tick labels
    float fx = plot.x_range.x + (plot.x_range.y - plot.x_range.x) * float(i) / 5.0f;
    float fy = plot.y_range.x + (plot.y_range.y - plot.y_range.x) * float(i) / 5.0f;
    OIIO::ImageBufAlgo::render_line(img, px(fx), y0, px(fx), y1, grid);
    OIIO::ImageBufAlgo::render_line(img, x0, py(fy), x1, py(fy), grid);
    OIIO::ImageBufAlgo::render_text(img, px(fx) - 10, y1 + 20, tick_label(fx), 14, kFont, black);
    OIIO::ImageBufAlgo::render_text(img, 16, py(fy) + 5, tick_label(fy), 14, kFont, black);
  }
  OIIO::ImageBufAlgo::render_box(img, x0, y0, x1, y1, black);
  FittedText title = fit_text(plot.title, 20, plot.width - x0 - 8);
  // The title above the y label's rows: the label starts left of x0 and ran into the title.
  OIIO::ImageBufAlgo::render_text(img, x0, 22, title.text, title.size, kFont, black);
  OIIO::ImageBufAlgo::render_text(img, (x0 + x1) / 2 - 40, plot.height - 18, plot.x_label, 16, kFont, black);
  OIIO::ImageBufAlgo::render_text(img, 8, y0 - 6, plot.y_label, 16, kFont, black);

  // Points outside the axes are drawn on the border (OIIO's drawing does not clip).
  auto inside = [&](glm::vec2 p) {
    return glm::vec2(std::clamp(p.x, std::min(plot.x_range.x, plot.x_range.y), std::max(plot.x_range.x, plot.x_range.y)),
                     std::clamp(p.y, std::min(plot.y_range.x, plot.y_range.y), std::max(plot.y_range.x, plot.y_range.y)));
  };
  int legend_y = y0 + 10;
  for (const PlotSeries& s : plot.series) {
    const float c[3] = {s.color.r, s.color.g, s.color.b};
    for (size_t i = 0; i < s.points.size(); ++i) {
      if (!std::isfinite(s.points[i].x) || !std::isfinite(s.points[i].y)) continue;
      glm::vec2 p = inside(s.points[i]);
      if (s.lines && i + 1 < s.points.size() && std::isfinite(s.points[i + 1].x) && std::isfinite(s.points[i + 1].y)) {
        glm::vec2 q = inside(s.points[i + 1]);
        OIIO::ImageBufAlgo::render_line(img, px(p.x), py(p.y), px(q.x), py(q.y), c);
      }
      if (s.markers && p == s.points[i])
        OIIO::ImageBufAlgo::render_box(img, px(p.x) - 2, py(p.y) - 2, px(p.x) + 2, py(p.y) + 2, c, true);
    }
    OIIO::ImageBufAlgo::render_box(img, x1 + 14, legend_y - 8, x1 + 30, legend_y, c, true);
    OIIO::ImageBufAlgo::render_text(img, x1 + 36, legend_y, s.label, 14, kFont, black);
    legend_y += 22;
  }

  std::filesystem::path tmp = path.parent_path() / (path.stem().string() + ".tmp-" + std::to_string(getpid()) + ".png");
  if (!img.write(tmp.string())) throw InputError(path.string(), 0, "", "cannot write plot: " + img.geterror());
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw InputError(path.string(), 0, "", "cannot write plot: " + ec.message());
}

}  // namespace forest
