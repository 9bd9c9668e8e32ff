// Log records: the event and its fields as text or as one JSON object, and nothing at
// all for a record whose level is off.
#include <catch2/catch.hpp>

#include <sstream>

#include <algorithm>
#include <vector>

#include <spdlog/spdlog.h>
#include <spdlog/sinks/ostream_sink.h>

#include "app/log.hpp"

using namespace fts::server;

namespace {

// Records go to `out` with only the message (%v) of the pattern; returns the logger.
std::shared_ptr<spdlog::logger> capture(std::ostringstream& out) {
  auto logger = std::make_shared<spdlog::logger>("capture", std::make_shared<spdlog::sinks::ostream_sink_st>(out));
  logger->set_pattern("%v");
  logger->set_level(spdlog::level::info);
  return logger;
}

}  // namespace

TEST_CASE("Log: text and JSON records, nothing below the level", "[server][log]") {
  static std::ostringstream out;  // static: the default logger outlives this test case
  const auto before = spdlog::default_logger();
  const nlohmann::ordered_json drops = {{"bad_crc", 2}};
  const std::string name = "a\"b";

  init_logging("info", "json");
  spdlog::set_default_logger(capture(out));
  log_record(spdlog::level::debug, "enemy_defeated", {{"enemy", 3}});
  CHECK(out.str().empty());
  log_record(spdlog::level::info, "stats",
             {{"players", std::size_t{2}}, {"name", name}, {"ok", true}, {"scale", 1.0}, {"tick", -1},
              {"model", "seed"}, {"drops", drops}});
  CHECK(out.str() == R"("event":"stats","players":2,"name":"a\"b","ok":true,"scale":1.0,"tick":-1,"model":"seed","drops":{"bad_crc":2}})"
                     "\n");

  out.str("");
  spdlog::drop("fts");
  init_logging("info", "text");
  spdlog::set_default_logger(capture(out));
  log_record(spdlog::level::info, "ready", {{"port", std::uint16_t{7777}}, {"name", name}, {"scale", 1.0}});
  CHECK(out.str() == "ready port=7777 name=a\"b scale=1.0\n");
  spdlog::drop("fts");
  spdlog::set_default_logger(before);
}

TEST_CASE("Log: records a client can cause are rate limited at info, with a summary", "[server][log]") {
  static std::ostringstream out;
  const auto before = spdlog::default_logger();
  init_logging("info", "text");
  spdlog::set_default_logger(capture(out));
  RateLimitedLog refusals("purchase_refused", 10000, 3);
  std::vector<spdlog::level::level_enum> levels;
  for (int i = 0; i < 1000; ++i) levels.push_back(refusals.level(100 + i));
  CHECK(std::count(levels.begin(), levels.end(), spdlog::level::info) == 3);
  CHECK(std::count(levels.begin(), levels.end(), spdlog::level::debug) == 997);
  refusals.flush(5000);
  CHECK(out.str().empty());  // the interval is not over
  refusals.flush(10100);
  CHECK(out.str() == "purchase_refused_summary at_debug=997 interval_ms=10000\n");
  out.str("");
  CHECK(refusals.level(10200) == spdlog::level::info);  // a new interval
  refusals.flush(20200);
  CHECK(out.str().empty());  // nothing demoted in it: no summary
  CHECK(refusals.demoted_total() == 997);
  spdlog::drop("fts");
  spdlog::set_default_logger(before);
}
