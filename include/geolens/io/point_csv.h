#pragma once
// Points as CSV text: "x,y" per line (pixels), read and written back exactly.

#include <cstddef>
#include <string>

#include "geolens/io/vector_data.h"

namespace geolens {

/// The most points a CSV table holds: 2^22 (4 194 304), as many as the vertices a map's features
/// are densified to (warp/densify.h). Ten million points took 1.6-1.9 GB through `geolens map`;
/// 2^22 take 0.8 GB and 3.2 s, one more is refused after 1.0 s and 0.24 GB.
constexpr size_t kMaxCsvPoints = size_t(1) << 22;

/// Parses CSV points: one point per line, its first two comma-separated fields x and y as
/// decimal numbers (pixels; spaces around them allowed), whatever follows them on the line
/// (",id,...") kept verbatim in PointTable::rest. The first line that is not blank is a header,
/// kept in PointTable::header, when neither of its first two fields is a number ("x,y",
/// "x,y,name"). Blank lines are skipped (so the points are not numbered by line); the carriage
/// returns that end a line are dropped ("\r\n" line ends are read as "\n").
/// @param name  where the text came from (a file name, "standard input"), for messages
/// @param max_points  the most points read (kMaxCsvPoints)
/// Throws InvalidInput("parse_point_csv: <name>:<line>: <what>") for a line whose first two
/// fields are not finite numbers (naming the line and what it holds), and for more than
/// `max_points` points.
PointTable parse_point_csv(const std::string& text, const std::string& name,
                           size_t max_points = kMaxCsvPoints);

/// parse_point_csv of the file at `path` (of at most 256 MiB, or 64 bytes a point where
/// `max_points` allows more). Throws InvalidInput naming the path if it cannot be read.
PointTable read_point_csv(const std::string& path, size_t max_points = kMaxCsvPoints);

/// The CSV text of `table`: its header line if any, then one "x,y<rest>" line per point, each
/// coordinate in the shortest decimal form that reads back to the same double (std::to_chars),
/// so write / read round-trips bit-exactly. Throws InvalidInput if rest does not have a row per
/// point or a point is not finite.
std::string point_csv_text(const PointTable& table);

}  // namespace geolens
