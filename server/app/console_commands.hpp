// The host's console commands (README "The host's console"): one table of {name, usage,
// handler, words}. The server answers a request with the command's handler; `help`, the
// error for an unknown command and the front end's usage come from the table, and the
// front end (`fts-server --console SOCKET CMD ARGS`) turns words into a request with it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace fts::server {

class GameHost;

struct ConsoleCommand {
  std::string_view name;
  std::string_view usage;  // the front end's words, e.g. "kick PLAYER [REASON]"
  std::string_view does;   // one line for help
  // The request (an object whose "cmd" is name) -> the reply: {"ok":true,...}, or an error.
  nlohmann::ordered_json (*handler)(GameHost& host, const nlohmann::json& request, std::uint64_t now_ms);
  // The words after the name -> the request's other fields; "" or why they do not fit.
  std::string (*from_words)(std::span<const std::string> words, nlohmann::json& request);
};

std::span<const ConsoleCommand> console_commands();

// One request in, one reply out, logged (`console request=... ok=...`). Bad input gets
// {"ok":false,"error":...} and changes nothing.
nlohmann::ordered_json console_command(GameHost& host, const nlohmann::json& request, std::uint64_t now_ms);

// One request line as the console socket gives it -> its reply. The line is read by
// fts::room::parse_json: text that is not JSON, an object with a key twice (the last one
// won, so {"cmd":"stats","cmd":"drain"} drained the server) or nesting deeper than
// kConsoleMaxDepth is refused and logged, and runs nothing.
inline constexpr int kConsoleMaxDepth = 8;
nlohmann::ordered_json console_line(GameHost& host, const std::string& line, std::uint64_t now_ms);

// `CMD ARGS...` -> the request object's JSON text, or "" with `error` set. A word that
// starts with '{' is a request object as is; an unknown name is sent for the server to refuse.
std::string console_request(const std::vector<std::string>& words, std::string& error);

}  // namespace fts::server
