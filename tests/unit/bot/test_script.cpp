// The bot script language: every step parses; a bad line is refused with its number.
#include <catch2/catch.hpp>

#include "bot/script.hpp"

using namespace fts::bot;

namespace {
std::string error_of(const std::string& text) {
  auto r = parse_script(text);
  if (auto* e = std::get_if<std::string>(&r)) return *e;
  return "";
}
}  // namespace

TEST_CASE("Bot scripts: every step of the documented language parses", "[bot][script]") {
  auto r = parse_script(R"(# a comment
timeout 30
wait connected
wait level_started
wait shop
wait ticks 100
move right 40
hunt
hunt 200
fire
buy mass
buy x
ready
play_again
expect coins >= 35
expect result ok
disconnect
reconnect
)");
  REQUIRE(std::holds_alternative<std::vector<Step>>(r));
  const auto& steps = std::get<std::vector<Step>>(r);
  REQUIRE(steps.size() == 17);
  CHECK(steps[0].op == Step::Op::set_timeout);
  CHECK(steps[5].op == Step::Op::move);
  CHECK(steps[5].word == "right");
  CHECK(steps[5].number == 40);
  CHECK(steps[6].number < 0);  // hunt without a count: through the following steps
  CHECK(steps[9].word == "m");
  CHECK(steps[10].word == "x");
  CHECK(steps[13].cmp == ">=");
  CHECK(steps[13].line == 15);
}

TEST_CASE("Bot scripts: bad lines are refused with their number", "[bot][script]") {
  CHECK(error_of("wait\n").rfind("line 1:", 0) == 0);
  CHECK(error_of("ready\nbuy sword\n").rfind("line 2: unknown item 'sword'", 0) == 0);
  CHECK(error_of("dance\n").rfind("line 1: unknown step 'dance'", 0) == 0);
  CHECK_FALSE(error_of("expect coins ~ 3\n").empty());
  // Numbers must be finite and sane: they feed tick and time arithmetic.
  CHECK_FALSE(error_of("timeout inf\n").empty());
  CHECK_FALSE(error_of("wait ticks 1e20\n").empty());
  CHECK_FALSE(error_of("move left nan\n").empty());
  CHECK_FALSE(error_of("expect coins >= 1e300\n").empty());
}

TEST_CASE("Bot scripts: comparisons", "[bot][script]") {
  CHECK(compare(36, ">=", 35));
  CHECK_FALSE(compare(34, ">=", 35));
  CHECK(compare(1, "==", 1));
  CHECK(compare(1, "!=", 2));
  CHECK_FALSE(compare(1, "??", 1));
}

TEST_CASE("Bot scripts: expect room CODE | any | refused REASON", "[bot][script][rooms]") {
  auto r = parse_script("expect room KXBQT\nexpect room any\nexpect room refused no_such_room\n");
  REQUIRE(std::holds_alternative<std::vector<Step>>(r));
  const auto& steps = std::get<std::vector<Step>>(r);
  REQUIRE(steps.size() == 3);
  CHECK(steps[0].op == Step::Op::expect_room);
  CHECK(steps[0].word == "KXBQT");
  CHECK(steps[1].word == "any");
  CHECK(steps[2].word == "refused");
  CHECK(steps[2].cmp == "no_such_room");
  CHECK(error_of("expect room\n").rfind("line 1:", 0) == 0);
  CHECK(error_of("expect room refused\n").rfind("line 1: expect room", 0) == 0);
  CHECK_FALSE(error_of("expect room KXBQT extra\n").empty());
  // The reason is an error code of the wire's table (codes.hpp), not any word.
  CHECK_THAT(error_of("expect room refused no_such_rom\n"), Catch::Contains("'no_such_rom' is no error code"));
  CHECK(error_of("expect room refused room_full\n").empty());
}
