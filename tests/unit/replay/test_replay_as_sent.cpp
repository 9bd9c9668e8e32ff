// Issue 27: a replay shows exactly what a client was sent. Two real protocol clients play
// against the GameHost in memory (time stepped by hand) while the room records; then the
// record is played by the client's Replay, and every snapshot a client received is
// compared, byte for byte in its full encoding (events window included), with the one
// the replay builds at that tick.
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>

#include "../../support/host_rig.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"
#include "replay/replay.hpp"

using namespace fts;

namespace {

std::vector<std::uint8_t> full_bytes(const protocol::Snapshot& s) {
  return protocol::encode_payload(protocol::Encoding::msgpack, {protocol::make_snapshot_msg(s, nullptr)});
}

}  // namespace

TEST_CASE("Replay: every snapshot a client was sent is the one the replay builds, byte for byte",
          "[replay][record]") {
  test::HostRig rig;
  rig.options.seed = 21;
  rig.start();
  test::RecordDir record("as-sent");
  rig.host->record_to(record.path.string(), "test");
  auto& a = rig.add("ann");
  auto& b = rig.add("bob");
  REQUIRE(rig.connect_all());
  a.send_command(protocol::CommandOp::ready, 0, rig.now);
  b.send_command(protocol::CommandOp::ready, 0, rig.now);
  std::vector<protocol::Snapshot> received;
  protocol::ClientEndpoint* late = nullptr;
  protocol::Snapshot late_first;
  std::size_t events_seen = 0;
  for (int i = 0; i < 3000; ++i) {
    // Both push around (falls, respawns, level ends and the shop make events).
    if (i % 7 == 0) {
      a.send_input({0, static_cast<std::int8_t>(i % 400 < 200 ? 1 : -1), static_cast<std::int8_t>(i % 300 < 150 ? 1 : -1), i % 50 == 0}, rig.now);
      b.send_input({0, static_cast<std::int8_t>(i % 500 < 250 ? -1 : 1), 1, false}, rig.now);
    }
    if (i % 97 == 0) b.send_command(protocol::CommandOp::buy, 'm', rig.now);
    if (i % 131 == 0) a.send_command(protocol::CommandOp::ready, 0, rig.now);
    if (i == 2000) {  // into ann's room by its code; its first snapshot is full: the whole window
      protocol::ClientConfig c;
      c.name = "cat";
      c.join = "join";
      c.room = a.welcome()->room;
      late = &rig.connect(c);
    }
    rig.tick();
    if (late != nullptr && late_first.tick == 0)
      for (auto& s : late->take_snapshots())
        if (late_first.tick == 0) late_first = s;
    for (auto& s : a.take_snapshots()) {
      events_seen += s.events.size();
      received.push_back(std::move(s));
    }
    b.take_snapshots();
  }

  REQUIRE(received.size() > 300);
  REQUIRE(events_seen > 0);

  rig.host.reset();  // the record's writer thread writes what is queued, then stops
  auto tape = client::load_history(record.path);
  REQUIRE(std::holds_alternative<client::Tape>(tape));
  client::Replay replay(std::move(std::get<client::Tape>(tape)));
  std::size_t compared = 0, with_events = 0;
  std::uint32_t newest_seen = 0;  // the newest event seq the client had before this snapshot
  for (const auto& sent : received) {
    replay.run_to(sent.tick);
    if (replay.state().tick != static_cast<std::int64_t>(sent.tick)) break;  // past the record's end
    protocol::Snapshot built = protocol::quantize(replay.snapshot());
    INFO("tick " << sent.tick);
    // Events (PROTOCOL.md 8.4): a delta carries the window's events newer than its base's,
    // so what the client got is the tail of the replay's window, and holds every event of
    // the window it had not seen yet.
    REQUIRE(sent.events.size() <= built.events.size());
    CHECK(std::equal(sent.events.begin(), sent.events.end(), built.events.end() - static_cast<std::ptrdiff_t>(sent.events.size())));
    for (const auto& e : built.events)
      if (e.seq > newest_seen)
        CHECK(std::find(sent.events.begin(), sent.events.end(), e) != sent.events.end());
    if (!sent.events.empty()) newest_seen = std::max(newest_seen, sent.events.back().seq);
    with_events += sent.events.empty() ? 0 : 1;
    // The rest, byte for byte in the full encoding.
    built.events = sent.events;
    REQUIRE(full_bytes(built) == full_bytes(sent));
    ++compared;
  }
  // The late joiner's full snapshot carries the recent window: the replay's, exactly.
  REQUIRE(late_first.tick > 0);
  CHECK_FALSE(late_first.events.empty());
  client::Replay again(std::move(std::get<client::Tape>(client::load_history(record.path))));
  again.run_to(late_first.tick);
  CHECK(full_bytes(protocol::quantize(again.snapshot())) == full_bytes(late_first));
  CHECK(replay.mismatch().empty());
  CHECK(compared + 2 >= received.size());
  CHECK(with_events > 3);
}
