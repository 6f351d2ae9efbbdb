#include "generators/methods/common/strokes_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "generators/core/input_error.h"
#include "generators/core/text_file.h"

namespace forest {

namespace {

int line_at(const std::string& text, size_t offset) {
  int line = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i)
    if (text[i] == '\n') ++line;
  return line;
}

std::string stroke_key(const Drawing& d, size_t i) {
  std::string k = "strokes[" + std::to_string(i) + "]";
  if (i < d.strokes.size() && !d.strokes[i].id.empty()) k += " (" + d.strokes[i].id + ")";
  return k;
}

void check_point(const Drawing& d, size_t i, glm::dvec2 p, const std::string& key) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    stroke_error(d, i, key, "coordinate is not a finite number");
  if (std::abs(p.x) > kMaxDrawingCoordinate || std::abs(p.y) > kMaxDrawingCoordinate)
    stroke_error(d, i, key, "coordinate beyond +-1e4 m");
}

// Checks common to both formats: ids, points, depths.
void validate(Drawing& d) {
  if (d.strokes.empty()) throw InputError(d.file, 0, "strokes", "the drawing has no strokes");
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < d.strokes.size(); ++i) {
    Stroke& s = d.strokes[i];
    if (s.id.empty()) s.id = "stroke" + std::to_string(i);
    if (!seen.emplace(s.id, i).second) stroke_error(d, i, "id", "duplicate id '" + s.id + "'");
    if (s.points.size() < 2) stroke_error(d, i, "points", "a stroke needs at least 2 points");
    if (s.points.size() > kMaxStrokePoints) stroke_error(d, i, "points", "more than 100000 points");
    for (glm::dvec2 p : s.points) check_point(d, i, p, "points");
    if (!s.depth.empty() && s.depth.size() != s.points.size())
      stroke_error(d, i, "depth", "needs one value per point (" + std::to_string(s.points.size()) + ")");
    for (double z : s.depth)
      if (!std::isfinite(z) || std::abs(z) > kMaxDrawingCoordinate)
        stroke_error(d, i, "depth", "not a finite number within +-1e4");
    if (s.level < 0 || s.level > 16) stroke_error(d, i, "level", "must be in [0, 16]");
    // SVG attributes arrive as raw bytes; they end up in JSON (drawing_to_json, model
    // metadata), which only holds UTF-8 text.
    for (auto [key, text] : {std::pair<const char*, const std::string*>{"id", &s.id}, {"role", &s.role}, {"parent", &s.parent}}) {
      try {
        (void)nlohmann::json(*text).dump();
      } catch (const nlohmann::json::type_error&) {
        stroke_error(d, i, key, "not valid UTF-8 text");
      }
      // Names are plain tokens in both formats, so that every accepted drawing can be
      // written as SVG and read back (a quote, '=', '<', '>' or '&' would end an attribute).
      if (text->find_first_of("\"'=<>&") != std::string::npos)
        stroke_error(d, i, key, "quotes, '=', '<', '>' and '&' are not supported in names");
    }
  }
  stroke_parents(d);  // parent errors now, not later in a method
}

double json_number(const Drawing& d, size_t i, const nlohmann::json& v, const std::string& key) {
  if (!v.is_number()) stroke_error(d, i, key, "expected a number");
  return v.get<double>();
}

}  // namespace

[[noreturn]] void stroke_error(const Drawing& drawing, size_t index, const std::string& key,
                               const std::string& what) {
  int line = index < drawing.strokes.size() ? drawing.strokes[index].line : 0;
  throw InputError(drawing.file, line, stroke_key(drawing, index) + "." + key, what);
}

Drawing parse_drawing_json(const std::string& text, const std::string& name) {
  Drawing d;
  d.file = name;
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name, line_at(text, e.byte), "", std::string("JSON syntax: ") + e.what());
  } catch (const nlohmann::json::exception& e) {  // e.g. out_of_range.406: a number beyond double
    throw InputError(name, 0, "", std::string("JSON: ") + e.what());
  }
  if (!root.is_object()) throw InputError(name, 1, "", "expected a JSON object");
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it.key() != "format" && it.key() != "version" && it.key() != "strokes")
      throw InputError(name, 0, it.key(), "unknown key (known: format, version, strokes)");
  if (root.contains("format") && root["format"] != "forest-drawing")
    throw InputError(name, 0, "format", "expected \"forest-drawing\"");
  if (!root.contains("strokes") || !root["strokes"].is_array())
    throw InputError(name, 0, "strokes", "missing array of strokes");
  const nlohmann::json& arr = root["strokes"];
  size_t search_from = text.find("\"strokes\"");
  for (size_t i = 0; i < arr.size(); ++i) {
    const nlohmann::json& js = arr[i];
    d.strokes.emplace_back();
    Stroke& s = d.strokes.back();
    if (!js.is_object()) stroke_error(d, i, "", "expected an object");
    for (auto it = js.begin(); it != js.end(); ++it)
      if (it.key() != "id" && it.key() != "role" && it.key() != "parent" && it.key() != "level" &&
          it.key() != "points" && it.key() != "depth")
        stroke_error(d, i, it.key(), "unknown key (known: id, role, parent, level, points, depth)");
    if (js.contains("id")) {
      if (!js["id"].is_string()) stroke_error(d, i, "id", "expected a string");
      s.id = js["id"].get<std::string>();
      // Line of the stroke: where its id first appears after "strokes" (ids are unique).
      size_t at = text.find("\"" + s.id + "\"", search_from == std::string::npos ? 0 : search_from);
      if (at != std::string::npos) s.line = line_at(text, at);
    }
    if (js.contains("role")) {
      if (!js["role"].is_string()) stroke_error(d, i, "role", "expected a string");
      s.role = js["role"].get<std::string>();
    }
    if (js.contains("parent")) {
      if (!js["parent"].is_string()) stroke_error(d, i, "parent", "expected a string (an id)");
      s.parent = js["parent"].get<std::string>();
    }
    if (js.contains("level")) {
      if (!js["level"].is_number_integer()) stroke_error(d, i, "level", "expected an integer");
      s.level = int(std::clamp<int64_t>(js["level"].get<int64_t>(), -1, 17));
    }
    if (!js.contains("points") || !js["points"].is_array())
      stroke_error(d, i, "points", "missing array of [x, y] points");
    for (const nlohmann::json& p : js["points"]) {
      if (!p.is_array() || p.size() != 2) stroke_error(d, i, "points", "each point is [x, y]");
      s.points.emplace_back(json_number(d, i, p[0], "points"), json_number(d, i, p[1], "points"));
      if (s.points.size() > kMaxStrokePoints) stroke_error(d, i, "points", "more than 100000 points");
    }
    if (js.contains("depth")) {
      if (!js["depth"].is_array()) stroke_error(d, i, "depth", "expected an array of numbers");
      for (const nlohmann::json& z : js["depth"]) s.depth.push_back(json_number(d, i, z, "depth"));
    }
  }
  validate(d);
  return d;
}

namespace {

// Attribute value of an SVG element's text, or empty.
std::string svg_attribute(const std::string& element, const std::string& name) {
  size_t at = 0;
  while ((at = element.find(name, at)) != std::string::npos) {
    bool word_start = at > 0 && (std::isspace((unsigned char)element[at - 1]));
    size_t eq = at + name.size();
    while (eq < element.size() && std::isspace((unsigned char)element[eq])) ++eq;
    if (word_start && eq < element.size() && element[eq] == '=') {
      size_t q = eq + 1;
      while (q < element.size() && std::isspace((unsigned char)element[q])) ++q;
      if (q < element.size() && (element[q] == '"' || element[q] == '\'')) {
        size_t end = element.find(element[q], q + 1);
        if (end != std::string::npos) return element.substr(q + 1, end - q - 1);
      }
    }
    at += name.size();
  }
  return {};
}

// Splits an SVG number list ("1,2 3 -4e1,5") into numbers; false on a malformed one.
bool svg_numbers(const std::string& s, size_t& pos, double& out) {
  while (pos < s.size() && (std::isspace((unsigned char)s[pos]) || s[pos] == ',')) ++pos;
  if (pos >= s.size()) return false;
  const char* begin = s.c_str() + pos;
  char* end = nullptr;
  out = std::strtod(begin, &end);
  if (end == begin) return false;
  pos += size_t(end - begin);
  return true;
}

}  // namespace

Drawing parse_drawing_svg(const std::string& text, const std::string& name) {
  Drawing d;
  d.file = name;
  if (text.find("<svg") == std::string::npos) throw InputError(name, 1, "", "not an SVG document (no <svg>)");
  size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    size_t end = text.find('>', at);
    if (end == std::string::npos) throw InputError(name, line_at(text, at), "", "unterminated element");
    std::string element = text.substr(at, end - at + 1);
    auto is = [&](const char* tag) {
      size_t n = std::strlen(tag);
      return element.compare(0, n, tag) == 0 && n < element.size() &&
             (std::isspace((unsigned char)element[n]) || element[n] == '/' || element[n] == '>');
    };
    const int element_line = line_at(text, at);
    if (element.rfind("<!--", 0) == 0) {  // comments may hold anything, '>' included
      size_t close = text.find("-->", at + 4);
      if (close == std::string::npos) throw InputError(name, element_line, "", "unterminated comment");
      at = close + 3;
      continue;
    }
    if (element[1] != '/' && element[1] != '?' && element[1] != '!' && !svg_attribute(element, "transform").empty())
      throw InputError(name, element_line, "transform",
                       "transforms are not supported; apply them to the coordinates before export");
    for (const char* shape : {"<rect", "<circle", "<ellipse", "<use", "<text"})
      if (is(shape))
        throw InputError(name, element_line, shape + 1,
                         "unsupported element; draw strokes as <polyline>, <polygon>, <line> or <path>");
    bool polyline = is("<polyline") || is("<polygon");
    bool closed = is("<polygon");
    bool path = is("<path");
    bool line = is("<line");
    if (polyline || path || line) {
      Stroke s;
      s.line = line_at(text, at);
      s.id = svg_attribute(element, "id");
      std::string role = svg_attribute(element, "class");
      if (!role.empty()) s.role = role;
      s.parent = svg_attribute(element, "data-parent");
      std::string level = svg_attribute(element, "data-level");
      std::string key = polyline ? "points" : path ? "d" : "x1";
      if (!level.empty()) {
        char* e = nullptr;
        long v = std::strtol(level.c_str(), &e, 10);
        if (*e != '\0') throw InputError(name, s.line, "data-level", "expected an integer");
        s.level = int(std::clamp<long>(v, -1, 17));
      }
      std::string data = svg_attribute(element, key);
      size_t pos = 0;
      double x = 0, y = 0;
      if (polyline) {
        while (svg_numbers(data, pos, x)) {
          if (!svg_numbers(data, pos, y)) {
            while (pos < data.size() && (std::isspace((unsigned char)data[pos]) || data[pos] == ',')) ++pos;
            throw InputError(name, s.line, "points", pos < data.size() ? "malformed number near '" + data.substr(pos, 12) + "'"
                                                                       : std::string("odd number of coordinates"));
          }
          s.points.emplace_back(x, -y);
          if (s.points.size() > kMaxStrokePoints) throw InputError(name, s.line, "points", "more than 100000 points");
        }
        while (pos < data.size() && std::isspace((unsigned char)data[pos])) ++pos;
        if (pos < data.size()) throw InputError(name, s.line, "points", "malformed number near '" + data.substr(pos, 12) + "'");
        if (closed && !s.points.empty()) s.points.push_back(s.points.front());
      } else if (line) {
        double c[4];
        const char* names[4] = {"x1", "y1", "x2", "y2"};
        for (int k = 0; k < 4; ++k) {
          std::string v = svg_attribute(element, names[k]);
          size_t vp = 0;
          if (!svg_numbers(v, vp, c[k]) || v.find_first_not_of(" \t", vp) != std::string::npos)
            throw InputError(name, s.line, names[k], "expected a number");
        }
        s.points = {{c[0], -c[1]}, {c[2], -c[3]}};
      } else {
        char command = 0;
        glm::dvec2 current(0.0), start(0.0);
        while (true) {
          while (pos < data.size() && (std::isspace((unsigned char)data[pos]) || data[pos] == ',')) ++pos;
          if (pos >= data.size()) break;
          char c = data[pos];
          if (std::isalpha((unsigned char)c) && c != 'e' && c != 'E') {
            if (std::string("MmLlHhVvZz").find(c) == std::string::npos)
              throw InputError(name, s.line, "d",
                               std::string("unsupported path command '") + c + "' (only M, L, H, V, Z; flatten curves first)");
            command = c;
            ++pos;
            if (c == 'Z' || c == 'z') {
              if (!s.points.empty()) s.points.emplace_back(start.x, -start.y);
            }
            continue;
          }
          if (command == 0 || command == 'Z' || command == 'z')
            throw InputError(name, s.line, "d", "coordinates without a command");
          glm::dvec2 p;
          if (command == 'H' || command == 'h' || command == 'V' || command == 'v') {
            double v = 0;
            if (!svg_numbers(data, pos, v)) throw InputError(name, s.line, "d", "malformed coordinate");
            if (s.points.empty()) throw InputError(name, s.line, "d", "a path starts with M");
            bool rel = command == 'h' || command == 'v';
            if (command == 'H' || command == 'h') p = {rel ? current.x + v : v, current.y};
            else p = {current.x, rel ? current.y + v : v};
          } else {
            if (!svg_numbers(data, pos, x) || !svg_numbers(data, pos, y))
              throw InputError(name, s.line, "d", "malformed coordinate pair");
            if (s.points.empty() && command != 'M' && command != 'm')
              throw InputError(name, s.line, "d", "a path starts with M");
            p = (command == 'm' || command == 'l') ? current + glm::dvec2(x, y) : glm::dvec2(x, y);
          }
          if (command == 'M' || command == 'm') {
            if (!s.points.empty()) throw InputError(name, s.line, "d", "one sub-path per stroke");
            start = p;
            command = command == 'M' ? 'L' : 'l';  // later pairs are line-tos (SVG rule)
          }
          current = p;
          s.points.emplace_back(p.x, -p.y);
          if (s.points.size() > kMaxStrokePoints) throw InputError(name, s.line, "d", "more than 100000 points");
        }
      }
      d.strokes.push_back(std::move(s));
    }
    at = end + 1;
  }
  validate(d);
  return d;
}

Drawing read_drawing(const std::filesystem::path& file) {
  std::string text = read_text_file(file, "drawing file");
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(file.string(), 0, "", "the drawing file is empty");
  std::string ext = file.extension().string();
  if (ext == ".json") return parse_drawing_json(text, file.string());
  if (ext == ".svg") return parse_drawing_svg(text, file.string());
  throw InputError(file.string(), 0, "", "unknown drawing format '" + ext + "' (use .json or .svg)");
}

std::string drawing_to_json(const Drawing& d) {
  nlohmann::ordered_json root;
  root["format"] = "forest-drawing";
  root["version"] = 1;
  root["strokes"] = nlohmann::ordered_json::array();
  auto round6 = [](double v) { return std::round(v * 1e6) / 1e6; };
  for (const Stroke& s : d.strokes) {
    nlohmann::ordered_json js;
    js["id"] = s.id;
    js["role"] = s.role;
    if (!s.parent.empty()) js["parent"] = s.parent;
    if (s.level != 0) js["level"] = s.level;
    js["points"] = nlohmann::ordered_json::array();
    for (glm::dvec2 p : s.points) js["points"].push_back({round6(p.x), round6(p.y)});
    if (!s.depth.empty()) {
      js["depth"] = nlohmann::ordered_json::array();
      for (double z : s.depth) js["depth"].push_back(round6(z));
    }
    root["strokes"].push_back(js);
  }
  // One stroke per line keeps the files diffable and small.
  std::string out = "{\"format\": \"forest-drawing\", \"version\": 1, \"strokes\": [\n";
  for (size_t i = 0; i < root["strokes"].size(); ++i)
    out += "  " + root["strokes"][i].dump() + (i + 1 < root["strokes"].size() ? ",\n" : "\n");
  out += "]}\n";
  return out;
}

std::string drawing_to_svg(const Drawing& d) {
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const Stroke& s : d.strokes)
    for (glm::dvec2 p : s.points) lo = glm::min(lo, glm::dvec2(p.x, -p.y)), hi = glm::max(hi, glm::dvec2(p.x, -p.y));
  glm::dvec2 size = hi - lo;
  char buf[160];
  std::snprintf(buf, sizeof buf, "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"%.4f %.4f %.4f %.4f\">\n",
                lo.x - 0.05 * size.x, lo.y - 0.05 * size.y, 1.1 * size.x, 1.1 * size.y);
  std::string out = buf;
  for (const Stroke& s : d.strokes) {
    out += "  <polyline id=\"" + s.id + "\" class=\"" + s.role + "\"";
    if (!s.parent.empty()) out += " data-parent=\"" + s.parent + "\"";
    if (s.level != 0) out += " data-level=\"" + std::to_string(s.level) + "\"";
    out += " fill=\"none\" stroke=\"black\" stroke-width=\"0.05\" points=\"";
    for (size_t k = 0; k < s.points.size(); ++k) {
      std::snprintf(buf, sizeof buf, "%s%.4f,%.4f", k ? " " : "", s.points[k].x, -s.points[k].y + 0.0);
      out += buf;
    }
    out += "\"/>\n";
  }
  return out + "</svg>\n";
}

std::vector<int> stroke_parents(const Drawing& d) {
  std::map<std::string, int> index;
  for (size_t i = 0; i < d.strokes.size(); ++i) index[d.strokes[i].id] = int(i);
  std::vector<int> parent(d.strokes.size(), -1);
  for (size_t i = 0; i < d.strokes.size(); ++i) {
    const Stroke& s = d.strokes[i];
    if (s.parent.empty()) continue;
    if (s.parent == s.id) stroke_error(d, i, "parent", "a stroke cannot be its own parent");
    auto it = index.find(s.parent);
    if (it == index.end()) stroke_error(d, i, "parent", "unknown stroke id '" + s.parent + "'");
    parent[i] = it->second;
  }
  // Cycles: walk up from every stroke; more steps than strokes means a loop.
  for (size_t i = 0; i < d.strokes.size(); ++i) {
    int p = parent[i];
    for (size_t steps = 0; p >= 0; ++steps) {
      if (steps > d.strokes.size() || size_t(p) == i)
        stroke_error(d, i, "parent", "the parent links form a cycle");
      p = parent[size_t(p)];
    }
  }
  return parent;
}

std::vector<const Stroke*> strokes_with_role(const Drawing& d, const std::string& role) {
  std::vector<const Stroke*> out;
  for (const Stroke& s : d.strokes)
    if (s.role == role) out.push_back(&s);
  return out;
}

void write_drawing_files(const std::filesystem::path& dir,
                         const std::vector<std::pair<std::string, std::string>>& files) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), 0, "--out", "cannot create folder: " + ec.message());
  for (const auto& [name, text] : files) {
    std::ofstream out(dir / name, std::ios::binary);
    out << text;
    if (!out) throw InputError((dir / name).string(), 0, "--out", "cannot write file");
  }
}

}  // namespace forest
