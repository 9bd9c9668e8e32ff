// The console's command table: help, the unknown-command error and the front end's words
// all come from it (app/console_commands.hpp).
#include <catch2/catch.hpp>

#include "../../support/host_rig.hpp"
#include "app/console_commands.hpp"

using namespace fts;

TEST_CASE("Console: help is the table, and every row answers", "[server][console]") {
  test::HostRig rig;
  rig.start();
  const auto help = rig.console(R"({"cmd":"help"})");
  REQUIRE(help["ok"] == true);
  const auto table = server::console_commands();
  REQUIRE(help["commands"].size() == table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    CHECK(help["commands"][i]["name"] == std::string(table[i].name));
    CHECK(help["commands"][i]["usage"] == std::string(table[i].usage));
    // Asked without its fields, a command answers for itself (ok or what it needs).
    if (table[i].name == "drain") continue;  // would stop the host
    const auto reply = rig.console(R"({"cmd":")" + std::string(table[i].name) + R"("})");
    if (reply["ok"] == false) CHECK(reply["error"].get<std::string>().find("unknown command") == std::string::npos);
  }
  const auto unknown = rig.console(R"({"cmd":"fly"})");
  CHECK(unknown["error"] ==
        "unknown command \"fly\"; commands: rooms, players, kick, ban, announce, close, drain, handover, stats, top, profile, help");
}

TEST_CASE("Console: the front end's words make the request", "[server][console]") {
  std::string error;
  auto request = [&](std::vector<std::string> words) {
    error.clear();
    return server::console_request(words, error);
  };
  CHECK(nlohmann::json::parse(request({"kick", "3", "too", "loud"})) ==
        nlohmann::json{{"cmd", "kick"}, {"player", 3}, {"reason", "too loud"}});
  CHECK(nlohmann::json::parse(request({"ban", "10.0.0.7", "5"})) ==
        nlohmann::json{{"cmd", "ban"}, {"address", "10.0.0.7"}, {"minutes", 5}});
  CHECK(nlohmann::json::parse(request({"players"})) == nlohmann::json{{"cmd", "players"}});
  CHECK(nlohmann::json::parse(request({"fly", "high"})) == nlohmann::json{{"cmd", "fly"}});  // the server refuses it
  CHECK(request({"kick", "x"}).empty());
  CHECK(error == "PLAYER must be a number, got \"x\"");
  CHECK(request({"close"}).empty());
  CHECK(error == "close ROOM");
  CHECK(request({"announce", " "}).empty());
  CHECK(request({}).empty());
  CHECK(error.find("kick PLAYER [REASON], ban ADDRESS [MINUTES]") != std::string::npos);
  CHECK(request({R"({"cmd":"rooms"})"}) == R"({"cmd":"rooms"})");
  // Words that are not UTF-8 are refused, not thrown (fts_fuzz_console found it).
  CHECK(request({"dra\xa1\x91"}).empty());
  CHECK(request({"announce", "caf\xe9"}).empty());
  CHECK(error == "the command and its words must be UTF-8 text");
}

// Issue 36 point 9: nlohmann keeps the last of two equal keys, so this line drained the host.
TEST_CASE("Console: a request with a key twice is refused and runs nothing", "[server][console]") {
  test::HostRig rig;
  rig.start();
  auto reply = rig.console(R"({"cmd":"stats","cmd":"drain"})");
  CHECK(reply["ok"] == false);
  CHECK(reply["error"] == R"(not a JSON request: key "cmd" appears twice in one object)");
  CHECK_FALSE(rig.host->draining());
  reply = rig.console(R"({"cmd":"announce","text":{"a":1,"a":2}})");
  CHECK(reply["error"] == R"(not a JSON request: key "a" appears twice in one object (at text.a))");
  reply = rig.console(R"({"cmd":"rooms","x":[1,{"k":1},{"k":1,"k":2}]})");
  CHECK(reply["error"] == R"(not a JSON request: key "k" appears twice in one object (at x[2].k))");
  // Equal keys in different objects are no repeat; the request runs.
  CHECK(rig.console(R"({"cmd":"stats","x":[{"k":1},{"k":1}],"y":{"cmd":1}})")["ok"] == true);
  // Nesting past kConsoleMaxDepth is refused before a tree is built.
  CHECK(rig.console(R"({"cmd":"stats","x":[[[[[[[1]]]]]]]})")["ok"] == true);  // 8 levels
  reply = rig.console(R"({"cmd":"stats","x":[[[[[[[[1]]]]]]]]})");
  CHECK(reply["error"] == "not a JSON request: the text nests at most 8 levels deep; this goes deeper (at x[0][0][0][0][0][0][0])");
  CHECK(rig.console("{\"cmd\":\"stats\"")["error"].get<std::string>().find("parse error") != std::string::npos);
  CHECK_FALSE(rig.host->draining());
}
