// The reliable ordered channel: messages with a reliable id (rid: 1, 2, 3, ...) are
// resent until a packet carrying them is acknowledged, and delivered to the receiver
// exactly once, in rid order. T is a message with a `rid` field (Command, Result).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "fts/protocol/reject.hpp"

namespace fts::protocol {

template <class T>
class ReliableSender {
 public:
  // Queues a message; assigns and returns its rid.
  std::uint32_t push(T message) {
    message.rid = next_rid_++;
    pending_.emplace(message.rid, Item{std::move(message), 0, false});
    return next_rid_ - 1;
  }

  // Pending messages to put in the packet `sequence` sent now: never sent, or last sent
  // at least resend_ms ago; at most max_count, oldest first.
  std::vector<T> collect(std::uint16_t sequence, std::uint64_t now_ms, std::uint64_t resend_ms,
                         std::size_t max_count) {
    std::vector<T> out;
    // Nothing to send: the packet's record is not touched (a record of an older packet
    // in its slot names another sequence, so an ack of this one finds nothing there).
    if (pending_.empty()) return out;
    if (in_packet_.empty()) in_packet_.resize(kPackets);  // made at the first message sent
    auto& in_packet = in_packet_[sequence % kPackets];
    in_packet.sequence = sequence;
    in_packet.rids.clear();
    for (auto& [rid, item] : pending_) {
      if (out.size() >= max_count) break;
      if (item.sent && now_ms < item.last_sent_ms + resend_ms) continue;
      item.sent = true;
      item.last_sent_ms = now_ms;
      out.push_back(item.message);
      in_packet.rids.push_back(rid);
    }
    return out;
  }

  // Does any message wait for a (re)send at now_ms?
  bool due(std::uint64_t now_ms, std::uint64_t resend_ms) const {
    for (const auto& [rid, item] : pending_)
      if (!item.sent || now_ms >= item.last_sent_ms + resend_ms) return true;
    return false;
  }

  // The packet `sequence` was acknowledged: what it carried is delivered.
  void on_acked(std::uint16_t sequence) {
    // Nothing pending, nothing to deliver: the records (cold memory) stay untouched; a
    // record's rids are never pending again (rids are not reused).
    if (pending_.empty() || in_packet_.empty()) return;
    auto& in_packet = in_packet_[sequence % kPackets];
    if (in_packet.sequence != sequence) return;
    for (auto rid : in_packet.rids) pending_.erase(rid);
    in_packet.rids.clear();
  }

  std::size_t pending() const { return pending_.size(); }

 private:
  struct Item {
    T message;
    std::uint64_t last_sent_ms;
    bool sent;
  };
  struct InPacket {
    std::uint16_t sequence = 0;
    std::vector<std::uint32_t> rids;
  };
  std::uint32_t next_rid_ = 1;
  std::map<std::uint32_t, Item> pending_;
  // What each of the last kPackets packets carried, by sequence: made at the first
  // message sent (8 KiB a channel, and a server's session has two). A session restored
  // from a journal or adopted from a peer has none until it sends: 512 sessions of 64
  // rooms adopted at once spent about a fifth of the adoption zeroing them (perf).
  static constexpr std::size_t kPackets = 256;
  std::vector<InPacket> in_packet_;
};

template <class T>
class ReliableReceiver {
 public:
  // How far ahead of the next expected rid a message may be (else out_of_range).
  static constexpr std::uint32_t kWindow = 1024;

  // Accepts one received message. Returns the reason when it is dropped: stale (already
  // delivered, or a duplicate still buffered) or out_of_range (too far ahead).
  std::optional<Reject> accept(const T& message) {
    if (message.rid < next_rid_) return Reject::stale;
    if (message.rid - next_rid_ >= kWindow) return Reject::out_of_range;
    if (!buffered_.emplace(message.rid, message).second) return Reject::stale;
    for (auto it = buffered_.find(next_rid_); it != buffered_.end(); it = buffered_.find(next_rid_)) {
      ready_.push_back(std::move(it->second));
      buffered_.erase(it);
      ++next_rid_;
    }
    return std::nullopt;
  }

  // Messages ready for the application, in rid order, each exactly once.
  std::vector<T> take() { return std::exchange(ready_, {}); }

  // Received out of order and held until the gap before them is filled.
  std::size_t buffered() const { return buffered_.size(); }

 private:
  std::uint32_t next_rid_ = 1;
  std::map<std::uint32_t, T> buffered_;
  std::vector<T> ready_;
};

}  // namespace fts::protocol
