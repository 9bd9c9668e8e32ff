// Structured logging over spdlog: every record is an event name plus fields, printed as
// "event key=value ..." (text) or one JSON object per line (json, for log shippers).
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

namespace fts::server {

// level: trace debug info warn error off; format: text | json.
void init_logging(const std::string& level, const std::string& format);

void log_record(spdlog::level::level_enum level, std::string_view event, const nlohmann::ordered_json& fields = {});

}  // namespace fts::server
