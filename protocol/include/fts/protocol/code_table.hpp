// One row per code a part of the wire names (an error's code, a result's code, a drop
// reason): the enum, its name and its meaning as PROTOCOL.md's table shows it. Names,
// parsing and the document's tables (test_code_tables.cpp) all come from these rows.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace fts::protocol {

template <class E>
struct CodeRow {
  E code;
  std::string_view name;     // as on the wire and in logs
  std::string_view meaning;  // the document's text (markdown), one line
  bool sent = true;          // false: a code only the C++ client makes, never on the wire
};

// Row i names enumerator i, so that a name is one index away (checked at compile time).
template <class E, std::size_t N>
constexpr bool rows_in_order(const std::array<CodeRow<E>, N>& rows) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(rows[i].code) != i || rows[i].name.empty()) return false;
  return true;
}

template <class E, std::size_t N>
constexpr std::string_view name_in(const std::array<CodeRow<E>, N>& rows, E code) {
  const auto i = static_cast<std::size_t>(code);
  return i < N ? rows[i].name : std::string_view("unknown");
}

template <class E, std::size_t N>
constexpr std::optional<E> code_in(const std::array<CodeRow<E>, N>& rows, std::string_view name) {
  for (const auto& r : rows)
    if (r.name == name) return r.code;
  return std::nullopt;
}

}  // namespace fts::protocol
