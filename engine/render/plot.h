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

// Writes atomically; InputError on failure.
void write_plot(const Plot& plot, const std::filesystem::path& path);

}  // namespace forest
