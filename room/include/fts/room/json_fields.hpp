// Strict field readers for JSON objects: every key must be known, every value checked,
// and every error names the path and the offending value.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fts::room {

struct FieldError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Fields {
 public:
  Fields(const nlohmann::json& obj, std::string path);
  // Throws FieldError for a key of the object outside `known`.
  void only(std::initializer_list<std::string_view> known) const;
  bool has(std::string_view key) const { return obj_.contains(key); }
  double number(std::string_view key) const;  // required, finite
  double number_or(std::string_view key, double fallback) const;
  std::int64_t integer(std::string_view key) const;
  std::int64_t integer_or(std::string_view key, std::int64_t fallback) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string(std::string_view key) const;
  std::string string_or(std::string_view key, std::string fallback) const;
  const nlohmann::json& at(std::string_view key) const;
  std::string path(std::string_view key) const;
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

 private:
  const nlohmann::json& obj_;
  std::string path_;
};

// Parses JSON text that came from outside (a file, a console line); on failure nothing,
// and `why` says why. Strict where nlohmann is lenient: an object with a key twice, at
// any depth, is refused naming the key and where it is (nlohmann keeps the last, so
// {"cmd":"stats","cmd":"drain"} drained the server), and so is text nesting deeper than
// `max_depth` containers (a container at the top is depth 1). Defined in json_strict.cpp.
inline constexpr int kNoDepthLimit = 0;
std::optional<nlohmann::json> parse_json(const std::string& text, std::string& why, int max_depth = kNoDepthLimit);

// Throws FieldError "<path>: must be > 0, got <v>" unless v > 0.
void require_positive(const Fields& f, std::string_view key, double v);

}  // namespace fts::room
