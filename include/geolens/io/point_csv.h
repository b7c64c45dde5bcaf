#pragma once
// Points as CSV text: "x,y" per line (pixels), read and written back exactly.

#include <string>

#include "geolens/io/vector_data.h"

namespace geolens {

/// Parses CSV points: one point per line, its first two comma-separated fields x and y as
/// decimal numbers (pixels; spaces around them allowed), whatever follows them on the line
/// (",id,...") kept verbatim in PointTable::rest. The first line that is not blank is a header,
/// kept in PointTable::header, when neither of its first two fields is a number ("x,y",
/// "x,y,name"). Blank lines are skipped (so the points are not numbered by line); the carriage
/// returns that end a line are dropped ("\r\n" line ends are read as "\n").
/// @param name  where the text came from (a file name, "standard input"), for messages
/// Throws InvalidInput("parse_point_csv: <name>:<line>: <what>") for a line whose first two
/// fields are not finite numbers (naming the line and what it holds).
PointTable parse_point_csv(const std::string& text, const std::string& name);

/// parse_point_csv of the file at `path`. Throws InvalidInput naming the path if it cannot be
/// read.
PointTable read_point_csv(const std::string& path);

/// The CSV text of `table`: its header line if any, then one "x,y<rest>" line per point, each
/// coordinate in the shortest decimal form that reads back to the same double (std::to_chars),
/// so write / read round-trips bit-exactly. Throws InvalidInput if rest does not have a row per
/// point or a point is not finite.
std::string point_csv_text(const PointTable& table);

}  // namespace geolens
