// The welcome and the match configuration (issue 36): every field config_fields.hpp marks
// client_row is a welcome key, no host field is, and PROTOCOL.md 4.3 lists exactly the
// welcome's keys; a welcome of an older server (without the physics keys) still reads.
#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <string>

#include "control_tables.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/welcome_size.hpp"
#include "fts/sim/config_fields.hpp"

using namespace fts::protocol;
namespace sim = fts::sim;

namespace {

std::set<std::string> welcome_keys() {
  std::set<std::string> out;
  std::apply([&](const auto&... f) { (out.emplace(f.key), ...); }, wire::kWelcomeFields);
  return out;
}

// The keys in the first column of the table under "### 4.3" (`a`, `b` rows name two).
std::set<std::string> documented_keys() {
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  REQUIRE(in);
  std::set<std::string> out;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("### 4.3 ", 0) == 0) in_section = true;
    else if (in_section && line.rfind("#", 0) == 0) break;
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    const std::string first = line.substr(1, line.find('|', 1) - 1);
    for (std::size_t at = first.find('`'); at != std::string::npos; at = first.find('`', at)) {
      const std::size_t end = first.find('`', at + 1);
      if (end == std::string::npos) break;
      out.insert(first.substr(at + 1, end - at - 1));
      at = end + 1;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("Welcome config: the welcome carries every CLIENT field of the match config, and no HOST field",
          "[protocol][welcome]") {
  const auto keys = welcome_keys();
  std::set<std::string> client, host;
  fts::fields::for_each(sim::kMatchConfigFields, [&](const auto& row) {
    (sim::is_client_key<decltype(row.kind)> ? client : host).insert(std::string(row.key));
  });
  for (const auto& k : {"tick_rate_hz", "model", "substeps", "frame_s", "arena_width_u", "arena_height_u",
                        "friction_per_frame", "friction_cutoff_u_per_s"})
    CHECK(client.count(k) == 1);  // what the step reads for the own ball's motion
  for (const auto& k : client) {
    INFO(k);
    CHECK(keys.count(k) == 1);
  }
  for (const auto& k : host) {
    INFO(k);
    CHECK((k == "max_players" || keys.count(k) == 0));  // max_players: the room's seats, a key of its own
  }
}

TEST_CASE("Welcome config: PROTOCOL.md 4.3 lists exactly the welcome's keys", "[protocol][welcome]") {
  const auto doc = documented_keys();
  const auto keys = welcome_keys();
  for (const auto& k : keys) {
    INFO("in the table, not in 4.3: " << k);
    CHECK(doc.count(k) == 1);
  }
  for (const auto& k : doc) {
    INFO("in 4.3, not in the table: " << k);
    CHECK(keys.count(k) == 1);
  }
}

TEST_CASE("Welcome config: a welcome without the physics keys reads them as the defaults", "[protocol][welcome]") {
  const std::string text =
      R"([{"t":"welcome","player_id":2,"token":"bcf8ef0b804a8357ee42dd8334a3619d","tick_rate_hz":50,)"
      R"("snapshot_rate_hz":10,"arena_width_u":400,"arena_height_u":200,"max_players":4,"timeout_ms":10000,)"
      R"("reconnect_window_ms":60000,"input_redundancy":3,"server_tick":9,"reconnected":false,"frame_s":0.01,)"
      R"("multiplier_upgrade_factor":1.1,"bank_interest_factor":1.1}])";
  auto d = decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  REQUIRE(d.ok());
  const auto& w = std::get<Welcome>(d->at(0));
  fts::sim::MatchConfig expect;
  expect.tick_rate_hz = 50;
  expect.arena_width_u = 400;
  expect.arena_height_u = 200;
  CHECK(w.match == expect);
  CHECK(w.tick_rate_hz() == 50);
  // A model the reader does not know is refused (the datagram is dropped, not guessed).
  std::string bad = text;
  bad.insert(bad.size() - 2, R"(,"model":"quantum")");
  CHECK_FALSE(decode_payload(Encoding::json, std::span(reinterpret_cast<const std::uint8_t*>(bad.data()), bad.size()))
                  .ok());
}

TEST_CASE("Welcome config: a tuned host's welcome fits in the reply to a hello - one with digits everywhere does not",
          "[protocol][welcome]") {
  Welcome w;
  w.timeout_ms = w.reconnect_window_ms = 3600000;
  CHECK(largest_welcome_bytes(w) <= kMinHelloBytes);
  const std::size_t plain = largest_welcome_bytes(w);
  // A host that changed the model, its sub-steps and the friction (three of the four
  // optional keys), the tick rate and the arena.
  w.match.model = fts::sim::Model::discrete;
  w.match.substeps = 16;
  w.match.friction_per_frame = 0.95;
  w.match.tick_rate_hz = 120;
  w.match.arena_width_u = 640;
  const std::size_t tuned = largest_welcome_bytes(w);
  INFO("default " << plain << " bytes, tuned " << tuned << " bytes");
  CHECK(plain <= 450);
  CHECK(tuned <= kMinHelloBytes);
  // 17 significant digits in every number: too long to send (fts-server refuses such a
  // configuration when it starts, match_settings.cpp).
  w.match.frame_s = 0.010000000000000002;
  w.match.arena_width_u = w.match.arena_height_u = 123456.78901234567;
  w.match.friction_per_frame = 0.9910000000000001;
  w.match.friction_cutoff_u_per_s = 1.0000000000000002;
  w.match.multiplier_upgrade_factor = w.match.bank_interest_factor = 1.1000000000000001;
  CHECK(largest_welcome_bytes(w) > kMinHelloBytes);
}
