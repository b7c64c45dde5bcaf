#pragma once
// Numbers and sizes as users write them (options, lens specs, scripts): one parser for every
// face, with one wording of what is wrong.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace geolens {

/// `text` as a finite number: all of it in strtod's syntax ("2", "0.25", "1e-3"; no spaces, no
/// "nan" or "inf"); empty otherwise.
std::optional<double> read_number(const std::string& text);
/// `text` as an int: all of it decimal digits with an optional sign ("100", "-1"; not "1e3" or
/// "2.0"), within int's range; empty otherwise.
std::optional<int> read_integer(const std::string& text);

/// read_number, or InvalidInput "WHAT: must be a number, got 'TEXT'".
double parse_number(const std::string& text, const std::string& what);
/// read_integer, or InvalidInput "WHAT: must be an integer, got 'TEXT'".
int parse_integer(const std::string& text, const std::string& what);

/// A count users write (a limit: "268435456", "1e9"): a number in read_number's syntax that is
/// whole and in [lo, hi]; else InvalidInput "WHAT: must be a whole number in [LO, HI], got 'TEXT'"
/// (or parse_number's message for what is no number).
uint64_t parse_count(const std::string& text, const std::string& what, uint64_t lo, uint64_t hi);

/// "WxH" (pixels): two integers joined by 'x', each in [lo, hi]. Throws InvalidInput naming
/// `what` ("--size: must be WxH, got '100'"; "--size: sides must be in [1, 16384], got '0x5'").
std::pair<int, int> parse_size(const std::string& text, const std::string& what, int lo, int hi);

}  // namespace geolens
