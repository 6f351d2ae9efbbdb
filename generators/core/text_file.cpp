#include "generators/core/text_file.h"

#include <fstream>
#include <sstream>

#include "generators/core/input_error.h"

namespace forest {

std::string read_text_file(const std::filesystem::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", "cannot open " + what);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace forest
