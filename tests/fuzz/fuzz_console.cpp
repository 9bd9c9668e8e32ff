// libFuzzer target: every byte string is what a console client writes to the host's
// console socket (--console-socket). The connection (server/net/console.cpp) cuts it
// into lines at '\n' (here the end of the input ends a line too), drops the line's
// trailing "\r\n", skips empty lines and closes on a line over kMaxLineBytes; the
// server's handler (console_line of app/console_commands.hpp) parses each line as strict
// JSON and answers it with console_command on the GameHost. The host here is in memory (as in
// tests/unit/server): two rooms, three connected clients; it is rebuilt when a request
// changed it (a kick, ban, close or drain). Each line is also split at spaces as the
// front end's words (`fts-server --console SOCKET CMD ARGS`, console_request) and that
// request is sent too. Properties: nothing escapes; every reply is an object whose "ok"
// is a bool, with a non-empty "error" when false, and is written (dump) and read back
// unchanged; the front end's request is JSON naming its command.
// Built and run by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <spdlog/spdlog.h>
#include <spdlog/sinks/null_sink.h>

#include "../support/host_rig.hpp"
#include "app/console_commands.hpp"
#include "app/log.hpp"
#include "fuzz_check.hpp"

using namespace fts;
using fuzz::check;
using fuzz::fail;

namespace {

constexpr std::size_t kMaxLineBytes = 65536;  // server/net/console.hpp ConsoleServer::kMaxLineBytes

struct Host {
  test::HostRig rig;
  std::size_t sessions = 0;

  Host() {
    rig.options.threads = 1;
    rig.start();
    protocol::ClientConfig ann, bob;
    ann.name = "ann";
    bob.name = "bob";
    bob.join = "create";
    rig.connect(ann);
    rig.connect(bob);
    if (!rig.connect_all()) fail("the console rig's clients did not connect");
    const server::Room* priv = nullptr;
    for (auto id : rig.host->room_ids())
      if (rig.host->room(id)->is_private()) priv = rig.host->room(id);
    if (!priv) fail("no private room");
    protocol::ClientConfig cy;
    cy.name = "cy";
    cy.join = "join";
    cy.room = priv->code();
    rig.connect(cy);
    if (!rig.connect_all()) fail("the console rig's third client did not connect");
    sessions = rig.host->endpoint().sessions().size();
  }
  // Whether a request changed what the next input should start from.
  bool changed() const {
    return rig.host->draining() || rig.host->room_ids().size() != 2 || rig.host->bans().size() != 0 ||
           rig.host->endpoint().sessions().size() != sessions;
  }
};

// One request line -> its reply line, as server/net/udp_server.cpp answers it.
std::string console_line(Host& h, const std::string& line) {
  const nlohmann::ordered_json reply = server::console_line(*h.rig.host, line, h.rig.now);
  check(reply.is_object() && reply.contains("ok") && reply["ok"].is_boolean(), "a reply is an object with \"ok\"");
  if (!reply["ok"].get<bool>())
    check(reply.contains("error") && reply["error"].is_string() && !reply["error"].get<std::string>().empty(),
          "a refusal says why");
  std::string text = reply.dump();  // throws on a string that is not UTF-8
  if (nlohmann::ordered_json::parse(text) != reply) fail("the reply changed through its text: " + text);
  h.rig.deliver();
  return text;
}

// The front end's words: the line split at spaces, as a shell would pass them.
void front_end(Host& h, const std::string& line) {
  std::vector<std::string> words;
  std::size_t at = 0;
  while (at <= line.size()) {
    const auto end = std::min(line.find(' ', at), line.size());
    if (end > at) words.push_back(line.substr(at, end - at));
    at = end + 1;
  }
  std::string error;
  const std::string request = server::console_request(words, error);
  if (request.empty()) {
    check(!error.empty(), "a front-end refusal says why");
    return;
  }
  if (words[0].front() != '{') {
    const auto j = nlohmann::json::parse(request, nullptr, false);
    check(j.is_object() && j.contains("cmd") && j["cmd"] == words[0], "the front end's request names its command");
  }
  (void)console_line(h, request);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool logging = [] {
    // The records are formatted (JSON, at every level) and thrown away.
    server::init_logging("trace", "json");
    auto logger = std::make_shared<spdlog::logger>("fuzz", std::make_shared<spdlog::sinks::null_sink_mt>());
    logger->set_level(spdlog::level::trace);
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)logging;
  static std::unique_ptr<Host> host;
  if (!host || host->changed()) host = std::make_unique<Host>();

  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    std::size_t at = 0;
    while (at < bytes.size()) {
      const auto nl = bytes.find('\n', at);
      const auto end = nl == std::string_view::npos ? bytes.size() : nl;
      std::string line(bytes.substr(at, end - at));
      at = end + 1;
      if (line.size() + 1 > kMaxLineBytes) break;  // the connection is closed
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
      if (line.empty()) continue;
      (void)console_line(*host, line);
      front_end(*host, line);
    }
    host->rig.tick();  // what the requests did reaches the clients
  } catch (const std::exception& e) {
    fail(std::string("exception escaped: ") + e.what());
  }
  return 0;
}
