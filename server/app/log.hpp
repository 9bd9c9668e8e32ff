// Structured logging over spdlog: every record is an event name plus fields, printed as
// "event key=value ..." (text) or one JSON object per line (json, for log shippers).
#pragma once

#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <variant>

#include <nlohmann/json.hpp>
// Only the level enum: the logger itself is log.cpp's (spdlog.h costs ~3 s of compile
// per translation unit, and most of the server includes this header).
#include <spdlog/common.h>

namespace fts::server {

// level: trace debug info warn error off; format: text | json.
void init_logging(const std::string& level, const std::string& format);

// One field of a record: a key and a value held by reference for the duration of the
// log_record call. Nothing is formatted (no JSON, no string) unless the record's level
// is on, so debug records on the tick path cost a level check when debug is off.
struct LogField {
  using Value = std::variant<std::int64_t, std::uint64_t, double, bool, std::string_view, const nlohmann::ordered_json*>;

  template <std::integral T>
    requires(!std::same_as<T, bool>)
  LogField(std::string_view k, T v) : key(k) {
    if constexpr (std::is_signed_v<T>) value = static_cast<std::int64_t>(v);
    else value = static_cast<std::uint64_t>(v);
  }
  LogField(std::string_view k, bool v) : key(k), value(v) {}
  LogField(std::string_view k, double v) : key(k), value(v) {}
  LogField(std::string_view k, const char* v) : key(k), value(std::string_view(v)) {}
  LogField(std::string_view k, std::string_view v) : key(k), value(v) {}
  LogField(std::string_view k, const std::string& v) : key(k), value(std::string_view(v)) {}
  LogField(std::string_view k, const nlohmann::ordered_json& v) : key(k), value(&v) {}

  std::string_view key;
  Value value;
};

void log_record(spdlog::level::level_enum level, std::string_view event, std::initializer_list<LogField> fields = {});

// Records a client can cause at will (refused commands): the first `info_burst` of each
// interval at info, the rest at debug, and at the end of an interval with some at debug
// one info summary `<event>_summary at_debug=N interval_ms=M` (16 000 refused buys are 16 000
// debug lines, not 16 000 info lines). Time is passed in.
class RateLimitedLog {
 public:
  RateLimitedLog(std::string event, std::uint64_t interval_ms = 10000, std::uint32_t info_burst = 5);
  // The level for one more record at now_ms.
  spdlog::level::level_enum level(std::uint64_t now_ms);
  // Writes the summary if the interval is over and some records went to debug.
  void flush(std::uint64_t now_ms);
  std::uint64_t demoted_total() const { return demoted_total_; }

 private:
  std::string summary_event_;
  std::uint64_t interval_ms_;
  std::uint32_t info_burst_;
  std::uint64_t interval_start_ms_ = 0;
  std::uint32_t at_info_ = 0;
  std::uint64_t demoted_ = 0;
  std::uint64_t demoted_total_ = 0;
};

}  // namespace fts::server
