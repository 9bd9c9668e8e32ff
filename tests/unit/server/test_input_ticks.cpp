// Input frames that name a tick (PROTOCOL.md 4.5, issue 28): a frame for a later tick
// waits for it and is applied exactly there (what a predicting client drew); a late one
// is applied at once and counted; a frame without a tick is applied when it arrives.
#include <catch2/catch.hpp>

#include <sstream>

#include "../../support/host_rig.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/room/record.hpp"

using namespace fts;

namespace {

const sim::Ball* ann_ball(const test::HostRig& rig) {
  const auto& m = rig.host->match();
  for (const auto& p : m.players)
    if (p.name == "ann" && p.ball) return sim::find_ball(m.world, p.ball);
  return nullptr;
}

}  // namespace

TEST_CASE("Input ticks: a frame for a later tick is applied at that tick, not when it arrives", "[server][input]") {
  test::HostRig rig;
  rig.options.seed = 4;
  rig.config.spawn_protection_s = 0;
  rig.start();
  auto& a = rig.add("ann");
  REQUIRE(rig.connect_all());
  a.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 400 && !(rig.host->match().phase == sim::Phase::playing && ann_ball(rig)); ++i) rig.tick();
  REQUIRE(ann_ball(rig) != nullptr);
  for (int i = 0; i < 50; ++i) rig.tick();  // at rest
  REQUIRE(ann_ball(rig)->vel.x == 0);
  const auto at = static_cast<std::uint32_t>(rig.host->match().tick + 30);
  a.send_input({0, 1, 0, false, at}, rig.now);  // right, from tick `at`
  while (rig.host->match().tick < at) {
    rig.tick();
    INFO("tick " << rig.host->match().tick);
    REQUIRE(ann_ball(rig)->vel.x == 0);  // waiting: not yet
  }
  rig.tick();  // tick `at` was stepped with it
  CHECK(ann_ball(rig)->vel.x > 0);
  CHECK(rig.host->input_timing().on_time == 1);
  // A frame for a tick already stepped is applied at once, and counted late.
  const auto past = static_cast<std::uint32_t>(rig.host->match().tick - 5);
  a.send_input({0, -1, 0, false, past}, rig.now);
  rig.tick();
  rig.tick();
  CHECK(rig.host->input_timing().late == 1);
  // Without a tick: at once (the old clients), counted as such.
  a.send_input({0, 0, 1, false, 0}, rig.now);
  rig.tick();
  rig.tick();
  CHECK(rig.host->input_timing().untimed >= 1);
  CHECK(ann_ball(rig)->vel.y > 0);
}

TEST_CASE("Input ticks: on the wire a frame's tick is a fifth element, written only when set", "[server][input]") {
  const std::string old_form = protocol::to_json_text({protocol::Input{7, {{3, 1, 0, false, 0}}}});
  CHECK(old_form.find("[3,1,0,0]") != std::string::npos);
  const std::string with_tick = protocol::to_json_text({protocol::Input{7, {{3, 1, 0, true, 1234}}}});
  CHECK(with_tick.find("[3,1,0,1,1234]") != std::string::npos);
  for (const char* text : {R"([{"t":"input","ack":0,"f":[[1,1,0,0,99]]}])", R"([{"t":"input","ack":0,"f":[[1,1,0,0]]}])"}) {
    const std::string s(text);
    const auto d = protocol::decode_payload(protocol::Encoding::json,
                                            std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()));
    REQUIRE(d.ok());
  }
  for (const char* text : {R"([{"t":"input","ack":0,"f":[[1,1,0]]}])", R"([{"t":"input","ack":0,"f":[[1,1,0,0,9,9]]}])"}) {
    const std::string s(text);
    const auto d = protocol::decode_payload(protocol::Encoding::json,
                                            std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()));
    CHECK_FALSE(d.ok());
  }
}

TEST_CASE("Input ticks: a record made with predicting clients' frames replays bit for bit", "[server][input]") {
  test::HostRig rig;
  rig.options.seed = 9;
  rig.start();
  test::RecordDir record("input-ticks");
  rig.host->record_to(record.path.string(), "test");
  auto& a = rig.add("ann");
  REQUIRE(rig.connect_all());
  a.send_command(protocol::CommandOp::ready, 0, rig.now);
  for (int i = 0; i < 600; ++i) {
    if (i % 9 == 0) {  // frames for a few ticks ahead, some late, as a predicting client's
      const auto tick = static_cast<std::uint32_t>(rig.host->match().tick + (i % 27 == 0 ? -2 : 7));
      a.send_input({0, static_cast<std::int8_t>(i % 200 < 100 ? 1 : -1), static_cast<std::int8_t>(i % 90 < 45 ? 1 : 0),
                    false, std::max<std::uint32_t>(tick, 1)},
                   rig.now);
    }
    rig.tick();
  }
  CHECK(rig.host->input_timing().on_time > 10);
  const auto live = sim::match_hash(rig.host->match());
  rig.host.reset();  // the record's writer thread writes what is queued, then stops
  auto replay = room::replay_history(record.path);
  REQUIRE(std::holds_alternative<room::ReplayReport>(replay));
  CHECK(std::get<room::ReplayReport>(replay).hashes_checked >= 60);
  CHECK(std::get<room::ReplayReport>(replay).final_hash == live);
}

// Issue 36 point 10: the lead bound was 100 ticks whatever the rate, 5 s at 20 Hz; it is
// kMaxLeadMs of the room's ticks.
TEST_CASE("Input ticks: the most a frame may lead is a second of the room's ticks", "[server][input]") {
  CHECK(server::max_lead_ticks(100) == 100);
  CHECK(server::max_lead_ticks(20) == 20);
  CHECK(server::max_lead_ticks(0.5) == 1);
  test::HostRig rig;
  rig.config.tick_rate_hz = 20;
  rig.options.tick_rate_hz = 20;
  rig.start();
  auto& a = rig.add("ann");
  REQUIRE(rig.connect_all());
  const auto now_tick = [&] { return static_cast<std::uint32_t>(rig.host->match().tick); };
  a.send_input({0, 1, 0, false, now_tick() + 15}, rig.now);  // 0.75 s ahead: waits for its tick
  for (int i = 0; i < 5; ++i) rig.tick();
  CHECK(rig.host->input_timing().too_early == 0);
  a.send_input({0, -1, 0, false, now_tick() + 40}, rig.now);  // 2 s ahead: no honest lead
  for (int i = 0; i < 5; ++i) rig.tick();
  CHECK(rig.host->input_timing().too_early == 1);
}
