// Drawings a user can make by hand: named 2D polylines (strokes) with a role, an optional
// parent and an optional level. Read by the sketch-based methods (`silhouettes`,
// `sketch-mrf`). Two formats:
//
// JSON (.json) — the format `forest make-inputs` writes:
//   { "format": "forest-drawing", "version": 1,
//     "strokes": [ { "id": "trunk", "role": "branch", "points": [[x, y], ...],
//                    "parent": "other id" (optional), "level": 0 (optional),
//                    "depth": [z, ...] (optional ground-truth depth per point) }, ... ] }
//   Coordinates are meters, +y up. Unknown keys are errors.
//
// SVG (.svg) — a subset a drawing program can export:
//   <polyline points="x,y x,y ..."/>, <polygon points=".."/> (closed: the first point is
//   repeated at the end), <line x1 y1 x2 y2/> and <path d="M x y L x y H x V y ... [Z]"/>
//   (M/L/H/V/Z and relative m/l/h/v/z, one sub-path per element; curves and arcs are
//   refused). Attributes: id, class (= role), data-parent, data-level. SVG's y axis points
//   down; it is flipped (y = -y_svg) so drawings look the same as in the SVG viewer.
//   `transform` attributes and <rect>, <circle>, <ellipse>, <use>, <text> are refused
//   (file:line error) rather than misread; other elements (<svg>, <g>, <title>, ...) are
//   ignored.
//
// Roles: "branch" (sketch-mrf strokes), "crown" (sketch-mrf crown curve), "axis" and
// "silhouette" (silhouettes levels), "leaf" (leaf silhouette). Errors (InputError naming
// file, line where known, and key): missing/empty file, syntax, NaN/inf or |coordinate| >
// 1e4, a stroke with < 2 points, duplicate ids, unknown or self-referencing parents, parent
// cycles.
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "generators/core/limits.h"

#include <glm/glm.hpp>

namespace forest {

struct Stroke {
  std::string id;
  std::string role = "branch";
  std::string parent;          // id of the parent stroke; empty for none
  int level = 0;
  std::vector<glm::dvec2> points;
  std::vector<double> depth;   // empty, or one ground-truth depth per point
  int line = 0;                // where the stroke starts in its file (0 when unknown)
};

struct Drawing {
  std::string file;  // for messages
  std::vector<Stroke> strokes;
};


// By extension: .json or .svg; anything else is an InputError.
Drawing read_drawing(const std::filesystem::path& file);
Drawing parse_drawing_json(const std::string& text, const std::string& name);
Drawing parse_drawing_svg(const std::string& text, const std::string& name);
// Deterministic JSON text (parse_drawing_json(write) == the drawing up to `line`).
std::string drawing_to_json(const Drawing& drawing);

// An SVG document of the drawing (polylines; y flipped; role in class, parent in
// data-parent). Depths are not stored (SVG has no third coordinate).
std::string drawing_to_svg(const Drawing& drawing);

// `forest make-inputs`: creates `dir` and writes each (file name, text) into it; InputError
// naming the folder or file when it cannot.
void write_drawing_files(const std::filesystem::path& dir,
                         const std::vector<std::pair<std::string, std::string>>& files);

// Index of each stroke's parent (-1 for none), after checking that parents exist, that no
// stroke is its own parent and that the parent links form no cycle.
std::vector<int> stroke_parents(const Drawing& drawing);

// Strokes with the given role, in file order.
std::vector<const Stroke*> strokes_with_role(const Drawing& drawing, const std::string& role);

// [[noreturn]] helper: InputError naming the stroke (file:line: strokes[i] (id): what).
[[noreturn]] void stroke_error(const Drawing& drawing, size_t index, const std::string& key,
                               const std::string& what);

}  // namespace forest
