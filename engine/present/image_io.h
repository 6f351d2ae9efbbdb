// Frames to and from image files through OpenImageIO (PNG, JPEG, EXR, ... by extension).
#pragma once
#include <filesystem>

#include "engine/render/renderer.h"

namespace forest {

// Writes atomically (temporary file in the same folder, then rename). InputError when the
// folder does not exist or the format is unknown.
void write_image(const FrameImage& image, const std::filesystem::path& path);
// Reads an 8-bit RGBA image (other channel counts are expanded). InputError on a bad file.
FrameImage read_image(const std::filesystem::path& path);
// Fails early (before any expensive work) when `path` cannot be written.
void check_output_path(const std::filesystem::path& path, const char* flag);

}  // namespace forest
