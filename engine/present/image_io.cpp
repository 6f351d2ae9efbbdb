#include "engine/present/image_io.h"

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "generators/core/input_error.h"

namespace forest {

void check_output_path(const std::filesystem::path& path, const char* flag) {
  std::error_code ec;
  std::filesystem::path dir = path.parent_path().empty() ? "." : path.parent_path();
  if (path.empty()) throw InputError(flag, 0, "", "output path is empty");
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(path.string(), 0, flag, "folder does not exist: " + dir.string());
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), 0, flag, "is a folder, expected a file name");
  if (access(dir.c_str(), W_OK) != 0) throw InputError(path.string(), 0, flag, "folder is not writable");
}

void write_image(const FrameImage& image, const std::filesystem::path& path) {
  std::filesystem::path tmp = path.parent_path() /
      (path.stem().string() + ".tmp-" + std::to_string(getpid()) + path.extension().string());
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw InputError(path.string(), 0, "", "unsupported image format '" + path.extension().string() + "'");
  OIIO::ImageSpec spec(int(image.width), int(image.height), 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  bool ok = out->open(tmp.string(), spec) &&
            out->write_image(OIIO::TypeDesc::UINT8, image.rgba.data()) && out->close();
  if (!ok) {
    std::string err = out->geterror();
    std::filesystem::remove(tmp);
    throw InputError(path.string(), 0, "", "cannot write image: " + err);
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw InputError(path.string(), 0, "", "cannot write image: " + ec.message());
  }
}

FrameImage read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string(), 0, "", "file not found");
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw InputError(path.string(), 0, "", "not a readable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > 65536 || spec.height > 65536 || spec.nchannels < 1)
    throw InputError(path.string(), 0, "", "unsupported image size or channels");
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data()))
    throw InputError(path.string(), 0, "", "corrupt image: " + in->geterror());
  FrameImage img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.rgba.resize(size_t(img.width) * img.height * 4);
  int c = spec.nchannels;
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    const uint8_t* p = &pixels[i * size_t(c)];
    uint8_t* q = &img.rgba[i * 4];
    q[0] = p[0];
    q[1] = c >= 3 ? p[1] : p[0];
    q[2] = c >= 3 ? p[2] : p[0];
    q[3] = c == 4 ? p[3] : (c == 2 ? p[1] : 255);
  }
  return img;
}

}  // namespace forest
