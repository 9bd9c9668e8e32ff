#include "app/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace fts::server {
namespace {
bool g_json = false;
}

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

void log_record(spdlog::level::level_enum level, std::string_view event, const nlohmann::ordered_json& fields) {
  if (!spdlog::should_log(level)) return;
  if (g_json) {
    nlohmann::ordered_json rec;
    rec["event"] = event;
    if (fields.is_object())
      for (const auto& [k, v] : fields.items()) rec[k] = v;
    const std::string text = rec.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    spdlog::log(level, "{}", std::string_view(text).substr(1));  // drop the opening brace
    return;
  }
  std::string line(event);
  if (fields.is_object()) {
    for (const auto& [k, v] : fields.items()) {
      line += ' ';
      line += k;
      line += '=';
      line += v.is_string() ? v.get<std::string>() : v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
  }
  spdlog::log(level, "{}", line);
}

}  // namespace fts::server
