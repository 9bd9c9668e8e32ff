#include "app/log.hpp"

#include <spdlog/spdlog.h>
#include <spdlog/sinks/stdout_color_sinks.h>

namespace fts::server {
namespace {

bool g_json = false;

std::string json_text(const nlohmann::ordered_json& j) {
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A field's value as JSON text, except that a text record prints strings unquoted.
std::string value_text(const LogField::Value& value, bool json) {
  return std::visit(
      [json](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, const nlohmann::ordered_json*>) return json_text(*v);
        else if constexpr (std::is_same_v<T, std::string_view>) return json ? json_text(std::string(v)) : std::string(v);
        else return json_text(v);
      },
      value);
}

}  // namespace

void init_logging(const std::string& level, const std::string& format) {
  g_json = format == "json";
  auto logger = spdlog::stderr_color_mt("fts");
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(level));
  // JSON: the pattern opens the object with the time and level; log_record writes the
  // rest of the object (its fields, without the opening brace).
  if (g_json) {
    spdlog::set_pattern(R"({"ts":"%Y-%m-%dT%H:%M:%S.%eZ","level":"%l",%v)", spdlog::pattern_time_type::utc);
  } else {
    spdlog::set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%^%l%$] %v");
  }
  spdlog::flush_on(spdlog::level::info);
}

void log_record(spdlog::level::level_enum level, std::string_view event, std::initializer_list<LogField> fields) {
  if (!spdlog::should_log(level)) return;
  std::string line;
  if (g_json) {
    line = "\"event\":" + json_text(std::string(event));
    for (const auto& f : fields) line += "," + json_text(std::string(f.key)) + ":" + value_text(f.value, true);
    line += '}';
  } else {
    line = event;
    for (const auto& f : fields) {
      line += ' ';
      line += f.key;
      line += '=';
      line += value_text(f.value, false);
    }
  }
  spdlog::log(level, "{}", line);
}

RateLimitedLog::RateLimitedLog(std::string event, std::uint64_t interval_ms, std::uint32_t info_burst)
    : summary_event_(std::move(event) + "_summary"), interval_ms_(interval_ms), info_burst_(info_burst) {}

spdlog::level::level_enum RateLimitedLog::level(std::uint64_t now_ms) {
  flush(now_ms);
  if (at_info_ < info_burst_) {
    ++at_info_;
    return spdlog::level::info;
  }
  ++demoted_;
  ++demoted_total_;
  return spdlog::level::debug;
}

void RateLimitedLog::flush(std::uint64_t now_ms) {
  if (now_ms < interval_start_ms_ + interval_ms_) return;
  if (demoted_ > 0)
    log_record(spdlog::level::info, summary_event_, {{"at_debug", demoted_}, {"interval_ms", interval_ms_}});
  interval_start_ms_ = now_ms;
  at_info_ = 0;
  demoted_ = 0;
}

}  // namespace fts::server
