#include "engine/scene/heightmap.h"
#include "generators/core/limits.h"

#include <algorithm>
#include <cmath>

#include <OpenImageIO/imageio.h>

#include "generators/core/input_error.h"

namespace forest {

float Heightmap::sample(float u, float v) const {
  float x = std::clamp(u, 0.0f, 1.0f) * float(width - 1), y = std::clamp(v, 0.0f, 1.0f) * float(height - 1);
  uint32_t x0 = std::min(uint32_t(x), width > 1 ? width - 2 : 0), y0 = std::min(uint32_t(y), height > 1 ? height - 2 : 0);
  uint32_t x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  float tx = x - float(x0), ty = y - float(y0);
  auto at = [&](uint32_t i, uint32_t j) { return values[size_t(j) * width + i]; };
  float a = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
  float b = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
  return a + (b - a) * ty;
}

Heightmap read_heightmap(const std::filesystem::path& file, const char* key) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw InputError(file.string(), 0, key, "file not found");
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw InputError(file.string(), 0, key, "not a readable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 2 || spec.height < 2 || spec.width > kMaxImageSide || spec.height > kMaxImageSide || spec.nchannels < 1)
    throw InputError(file.string(), 0, key,
                     "heightmap must be 2.." + std::to_string(kMaxImageSide) + " pixels per side, got " + std::to_string(spec.width) + "x" +
                         std::to_string(spec.height));
  Heightmap h;
  h.width = uint32_t(spec.width);
  h.height = uint32_t(spec.height);
  h.values.resize(size_t(h.width) * h.height);
  // Only the first channel; OIIO converts integer formats to [0, 1] floats.
  if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, h.values.data()))
    throw InputError(file.string(), 0, key, "corrupt image: " + in->geterror());
  for (float v : h.values)
    if (!std::isfinite(v)) throw InputError(file.string(), 0, key, "heightmap holds a non-finite value");
  return h;
}

}  // namespace forest
