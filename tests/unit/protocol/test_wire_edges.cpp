// Corners PROTOCOL.md states after issue 36 (point 5), checked here against the server
// endpoint: a frame with seq 0 (4.5), a packet sequence exactly 32768 ahead (2, 5.7.2),
// a hello with another message in its datagram (4.1). Time is stepped by hand.
#include <catch2/catch.hpp>

#include "harness.hpp"

using namespace fts::protocol;
using namespace fts::protocol::test;

namespace {

struct OnePlayer {
  Harness h;
  Peer* p = nullptr;
  std::uint32_t session = 0;

  OnePlayer() {
    p = &h.add_client(named("ann"));
    p->client.connect(h.now);
    REQUIRE(h.run_until([&] { return p->client.state() == ClientState::connected; }, 1000));
    h.run_until([&] { return false; }, h.now + 50);
    h.server.take_events();
    h.server.take_inputs();
    p->client.send_input({0, 0, 0, false}, h.now);
    auto out = p->client.take_datagrams();
    REQUIRE_FALSE(out.empty());
    session = read_header(out[0])->session;
  }

  // A datagram of the client's session with this packet sequence, sealed with its keys.
  void send(std::uint16_t sequence, const std::vector<Message>& messages) {
    Header hd;
    hd.encoding = Encoding::json;
    hd.session = session;
    hd.sequence = sequence;
    h.server.receive(p->address, seal_as(p->client, hd, messages), h.now);
  }
};

}  // namespace

TEST_CASE("Edges: an input frame with seq 0 is ignored, the others of the input apply", "[protocol][edges]") {
  OnePlayer o;
  const auto before = o.h.server.rejects().total();
  o.send(1000, {Input{0, {InputFrame{0, 1, 0, true, 0}, InputFrame{5, -1, 0, false, 0}}}});
  const auto inputs = o.h.server.take_inputs();
  REQUIRE(inputs.size() == 1);
  CHECK(inputs[0].frame.seq == 5);
  CHECK(inputs[0].frame.move_x == -1);
  CHECK(o.h.server.rejects().total() == before);  // not counted: it is simply no frame
}

TEST_CASE("Edges: a packet sequence exactly 32768 ahead is stale, and moves the replay window",
          "[protocol][edges][sealed]") {
  OnePlayer o;
  o.send(1000, {Ping{}});  // the newest opened: 1000
  const auto stale = o.h.server.rejects()[Reject::stale];
  const auto replayed = o.h.server.rejects()[Reject::replayed];
  // 2: not newer ((a - b) mod 65536 is not < 32768) and over 32 behind: stale. 5.7.2 took
  // it as 32768 ahead (the tie stays in the newest's block), so it opened first.
  o.send(1000 + 32768, {Input{0, {InputFrame{1, 1, 0, false, 0}}}});
  CHECK(o.h.server.rejects()[Reject::stale] == stale + 1);
  CHECK(o.h.server.take_inputs().empty());
  // The sender's next packet is now 32767 behind the newest opened: replayed.
  o.send(1001, {Input{0, {InputFrame{2, 1, 0, false, 0}}}});
  CHECK(o.h.server.rejects()[Reject::replayed] == replayed + 1);
  CHECK(o.h.server.take_inputs().empty());
}

TEST_CASE("Edges: a hello with an input in its datagram is dropped unanswered", "[protocol][edges]") {
  Harness h;
  Header hd;
  hd.encoding = Encoding::json;
  const auto bytes = encode_datagram(
      hd, {Hello{"ann", "", "", std::string(600, '.'), "00000000000000a1"}, Input{0, {InputFrame{1, 1, 0, false, 0}}}});
  REQUIRE(bytes.size() >= kMinHelloBytes);
  const auto before = h.server.rejects()[Reject::unexpected];
  h.server.receive("10.0.0.5:5000", bytes, h.now);
  CHECK(h.server.rejects()[Reject::unexpected] == before + 1);
  CHECK(h.server.take_datagrams().empty());
}
