// Packet sequence numbers and acks for one connection (one per endpoint side): which
// of our packets the peer acknowledged (for the reliable channel and the RTT), and what
// to acknowledge in our next header. Sequences run 1..65535 and wrap to 1; 0 is never
// sent, so an ack of 0 means "nothing received yet".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "fts/protocol/header.hpp"

namespace fts::protocol {

class AckWindow {
 public:
  // Takes the next outgoing sequence, remembers when it was sent, and fills the header's
  // sequence, ack and ack_bits.
  void stamp(Header& header, std::uint64_t now_ms);

  // Records an incoming header. Returns false for a duplicate or a packet more than 32
  // behind the newest (drop it). Otherwise appends our newly acknowledged sequences.
  bool on_receive(const Header& header, std::uint64_t now_ms, std::vector<std::uint16_t>& newly_acked);

  // Smoothed round-trip time (ms) of the network alone: each sample is the time from
  // sending a packet to the arrival of the header that acks it, minus the ack delay that
  // header reports. 0 until the first sample.
  double rtt_ms() const { return rtt_ms_; }
  std::uint64_t packets_acked() const { return packets_acked_; }
  std::uint64_t packets_sent() const { return packets_sent_; }

 private:
  struct Sent {
    std::uint16_t sequence = 0;
    bool valid = false;
    bool acked = false;
    std::uint64_t time_ms = 0;
  };
  void ack_one(std::uint16_t seq, std::uint64_t now_ms, std::optional<std::uint16_t> delay_ms,
               std::vector<std::uint16_t>& out);

  std::uint16_t next_sequence_ = 1;
  std::array<Sent, 256> sent_{};
  bool have_received_ = false;
  std::uint16_t latest_received_ = 0;
  std::uint64_t latest_received_ms_ = 0;  // when latest_received_ arrived (for ack delays)
  std::uint32_t received_bits_ = 0;
  // What the peer's headers acknowledged so far, as the newest such header's ack and bits
  // (with the bits before it folded in): a header's bits repeat its predecessors' 31 of 32
  // times, and only the new ones are looked up in sent_ (33 slots a datagram otherwise).
  bool have_peer_ack_ = false;
  std::uint16_t peer_ack_ = 0;
  std::uint32_t peer_ack_bits_ = 0;
  double rtt_ms_ = 0;
  std::uint64_t rtt_samples_ = 0;
  std::uint64_t packets_acked_ = 0;
  std::uint64_t packets_sent_ = 0;
};

}  // namespace fts::protocol
