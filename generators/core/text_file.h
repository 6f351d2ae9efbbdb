// Whole input files as text, for the readers of species, drawings, learned models and
// samples: one place that turns an unreadable file into an InputError naming it.
#pragma once
#include <filesystem>
#include <string>

namespace forest {

// The bytes of `file`; InputError "<file>: cannot open <what>" when it cannot be opened.
std::string read_text_file(const std::filesystem::path& file, const std::string& what = "file");

}  // namespace forest
