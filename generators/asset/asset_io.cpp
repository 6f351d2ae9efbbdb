// The .glb files: atomic writes and reads (glb_writer.cpp and glb_reader.cpp convert). tinygltf
// and stb are compiled here, once for the whole program. Debian puts stb in /usr/include/stb/,
// where tiny_gltf.h does not look, so stb is included first by path.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include "generators/asset/asset_io.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>

#include "generators/core/input_error.h"

namespace forest {

void write_file_atomic(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path dir = path.parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw InputError(path.string(), 0, "", "directory " + dir.string() + " does not exist");
  // A temporary name no other writer uses: other threads (a counter), processes (the pid)
  // and machines sharing the folder (the host name) each write their own, and the rename
  // lets exactly one complete file stand.
  static std::atomic<uint64_t> writes{0};
  char host[256] = "host";
  if (::gethostname(host, sizeof host - 1) != 0) std::snprintf(host, sizeof host, "host");
  host[sizeof host - 1] = 0;
  fs::path tmp = path;
  tmp += ".tmp-" + std::string(host) + "-" + std::to_string(::getpid()) + "-" + std::to_string(writes++);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path.string(), 0, "", "cannot write (permission denied or not a directory?)");
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      throw InputError(path.string(), 0, "", "write failed (disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw InputError(path.string(), 0, "", "cannot rename temporary file: " + ec.message());
  }
}

void save_glb(const TreeModel& model, const std::filesystem::path& path) {
  std::vector<uint8_t> bytes = encode_glb(model);
  write_file_atomic(path, bytes);
}

TreeModel load_glb(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), 0, "", std::filesystem::exists(path, ec) ? "not a regular file" : "file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "", "cannot open file");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path.string(), 0, "", "read error");
  return decode_glb(bytes, path.string());
}

}  // namespace forest
