#include "generators/bake/priority/priority_names.h"

namespace forest {

std::string_view priority_name(Priority p) {
  switch (p) {
    case Priority::random: return "random";
    case Priority::density: return "density";
    case Priority::orientation: return "orientation";
    case Priority::combined: return "combined";
    case Priority::layered: return "layered";
  }
  return "random";
}

std::optional<Priority> parse_priority(std::string_view name) {
  for (Priority p : {Priority::random, Priority::density, Priority::orientation, Priority::combined, Priority::layered})
    if (priority_name(p) == name) return p;
  return std::nullopt;
}

}  // namespace forest
