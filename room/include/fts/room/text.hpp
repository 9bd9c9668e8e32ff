// Small text conversions shared by the command-line tools.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace fts::room {

// The whole string as a number, or nothing ("12x", "", "1e999" fail).
std::optional<double> to_number(const std::string& s);
std::optional<std::int64_t> to_integer(const std::string& s);
// A 64-bit hash as 16 lower-case hex digits.
std::string hex16(std::uint64_t v);

}  // namespace fts::room
