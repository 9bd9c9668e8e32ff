#include "fts/protocol/ack.hpp"

#include <algorithm>
#include <bit>

namespace fts::protocol {

void AckWindow::stamp(Header& header, std::uint64_t now_ms) {
  header.sequence = next_sequence_++;
  if (next_sequence_ == 0) next_sequence_ = 1;  // 0 is never a sequence: ack 0 means "none yet"
  header.ack = latest_received_;
  header.ack_bits = have_received_ ? received_bits_ : 0;
  header.ack_delay_ms = 0;
  if (have_received_ && now_ms > latest_received_ms_)
    header.ack_delay_ms = static_cast<std::uint16_t>(std::min<std::uint64_t>(now_ms - latest_received_ms_, 0xFFFF));
  Sent& slot = sent_[header.sequence % sent_.size()];
  slot = Sent{header.sequence, true, false, now_ms};
  ++packets_sent_;
}

void AckWindow::ack_one(std::uint16_t seq, std::uint64_t now_ms, std::optional<std::uint16_t> delay_ms,
                        std::vector<std::uint16_t>& out) {
  Sent& slot = sent_[seq % sent_.size()];
  if (!slot.valid || slot.acked || slot.sequence != seq) return;
  slot.acked = true;
  ++packets_acked_;
  out.push_back(seq);
  // Only the header's own `ack` comes with the time it waited at the peer; the packets
  // acknowledged by bits alone give no RTT sample.
  if (!delay_ms) return;
  const std::uint64_t in_flight = now_ms >= slot.time_ms ? now_ms - slot.time_ms : 0;
  const double sample = static_cast<double>(in_flight > *delay_ms ? in_flight - *delay_ms : 0);
  rtt_ms_ = rtt_samples_++ == 0 ? sample : rtt_ms_ + 0.1 * (sample - rtt_ms_);
}

bool AckWindow::on_receive(const Header& header, std::uint64_t now_ms,
                           std::vector<std::uint16_t>& newly_acked) {
  const std::uint16_t seq = header.sequence;
  if (seq == 0) return false;
  if (!have_received_) {
    have_received_ = true;
    latest_received_ = seq;
    latest_received_ms_ = now_ms;
    received_bits_ = 0;
  } else if (sequence_newer(seq, latest_received_)) {
    const unsigned shift = static_cast<std::uint16_t>(seq - latest_received_);
    if (shift < 32) {
      received_bits_ = (received_bits_ << shift) | (1u << (shift - 1));
    } else {
      received_bits_ = shift == 32 ? (1u << 31) : 0;
    }
    latest_received_ = seq;
    latest_received_ms_ = now_ms;
  } else {
    const unsigned behind = static_cast<std::uint16_t>(latest_received_ - seq);
    if (behind == 0 || behind > 32) return false;
    const std::uint32_t bit = 1u << (behind - 1);
    if (received_bits_ & bit) return false;
    received_bits_ |= bit;
  }
  if (header.ack == 0) return true;
  // The sequences an earlier header acknowledged (the newest one read, its ack no newer
  // than this one's), moved to this header's ack: bit i is header.ack - 1 - i.
  std::uint32_t seen = 0;
  bool ack_seen = false;
  const bool newest = !(have_peer_ack_ && sequence_newer(peer_ack_, header.ack));
  if (have_peer_ack_ && newest) {
    const unsigned d = static_cast<std::uint16_t>(header.ack - peer_ack_);
    if (d == 0) {
      seen = peer_ack_bits_;
      ack_seen = true;
    } else if (d <= 32) {
      seen = (d < 32 ? peer_ack_bits_ << d : 0u) | (1u << (d - 1));
    }
  }
  if (!ack_seen) ack_one(header.ack, now_ms, header.ack_delay_ms, newly_acked);
  for (std::uint32_t fresh = header.ack_bits & ~seen; fresh != 0; fresh &= fresh - 1) {
    const auto acked = static_cast<std::uint16_t>(header.ack - 1 - std::countr_zero(fresh));
    if (acked != 0) ack_one(acked, now_ms, std::nullopt, newly_acked);
  }
  // Kept only for an ack of a packet sent already (one of ours from the last 2^15): an ack
  // of a sequence not sent yet must not mark it seen for when it is.
  const auto last_sent = static_cast<std::uint16_t>(next_sequence_ == 1 ? 0xFFFF : next_sequence_ - 1);
  if (newest && packets_sent_ > 0 && !sequence_newer(header.ack, last_sent)) {
    peer_ack_bits_ = header.ack_bits | seen;
    peer_ack_ = header.ack;
    have_peer_ack_ = true;
  }
  return true;
}

}  // namespace fts::protocol
