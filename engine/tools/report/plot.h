// Small line/scatter plots written as PNG (OpenImageIO draws lines and DejaVu text): the
// figures of `forest report` and `forest bench`.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace forest {

struct PlotSeries {
  std::string label;
  std::vector<glm::vec2> points;
  glm::vec3 color{0.1f, 0.3f, 0.8f};
  bool lines = true;    // polyline through the points
  bool markers = false; // a small square at each point
};

struct Plot {
  std::string title, x_label, y_label;
  glm::vec2 x_range{0, 1}, y_range{0, 1};  // fixed axes (no autoscale: figures stay comparable)
  std::vector<PlotSeries> series;
  int width = 800, height = 560;
};

// Autoscaled range covering every point with a margin (for plots whose range is data).
glm::vec2 padded_range(const std::vector<PlotSeries>& series, int axis, float pad = 0.05f);

// `text` at the largest font size from `size` down to 12 that fits in `width` pixels; still
// too wide at 12 (a long device name or scene path in a bench title), it is cut at a whole
// UTF-8 character and ends in "...". The title of write_plot goes through it.
struct FittedText {
  std::string text;
  int size = 0;
};
FittedText fit_text(std::string text, int size, int width);

// Writes atomically; InputError on failure.
void write_plot(const Plot& plot, const std::filesystem::path& path);

}  // namespace forest
