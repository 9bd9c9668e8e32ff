// Snapshot delta encoding: a snapshot is sent against the last one the client
// acknowledged (full when there is none), quantized, and split into parts so that no
// datagram passes kMaxDatagramBytes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "fts/protocol/decoded.hpp"
#include "fts/protocol/header.hpp"
#include "fts/protocol/messages.hpp"

namespace fts::protocol {

// Payload budget of one datagram.
inline constexpr std::size_t kMaxPayloadBytes = kMaxDatagramBytes - kHeaderBytes - kSealTagBytes;

// One message holding `current` as a delta against `base` (nullptr: full). Both are
// quantized first (base normally is already).
// `tick_rate_hz` drives the motion prediction of the delta (0: plain differences).
SnapshotMsg make_snapshot_msg(const Snapshot& current, const Snapshot* base, std::uint32_t tick_rate_hz = 100);

// Where a velocity of v_q (1/16 u/s) moves a ball in `ticks` ticks at `tick_rate_hz`, in
// 1/16 u, rounded half away from zero; integers only, so both ends agree exactly.
std::int64_t predicted_step(std::int64_t v_q, std::uint32_t ticks, std::uint32_t tick_rate_hz);

// Splits a message into parts whose payloads (each encoded alone) fit `budget` bytes:
// balls and players spread over the parts; gone, left and events in part 0 (the oldest
// events are dropped if even that does not fit).
std::vector<SnapshotMsg> split_snapshot(SnapshotMsg message, Encoding encoding,
                                        std::size_t budget = kMaxPayloadBytes);
// The same into `parts`, reused: a message that fits in one part is swapped into
// parts[0] (no copy, no allocation once the lists have grown to size), which leaves
// `message` holding the old part; a longer one is copied and split.
void split_snapshot_into(SnapshotMsg& message, Encoding encoding, std::size_t budget,
                         std::vector<SnapshotMsg>& parts);

// Rebuilds a snapshot from all its parts and its base (nullptr for a full snapshot).
Decoded<Snapshot> apply_snapshot(const std::vector<SnapshotMsg>& parts, const Snapshot* base);

// A snapshot already quantized (quantize()), built once per tick and shared by the
// senders of every client: each keeps it as a possible base without a copy.
using SharedSnapshot = std::shared_ptr<const Snapshot>;

// Server side, one per client: remembers what was sent, and which tick was acknowledged.
class SnapshotSender {
 public:
  static constexpr std::size_t kHistory = 64;

  // A delta is made only against a base at most this many ticks old (default: 1 s at
  // 100 Hz); a client whose acknowledgements lag further gets a full snapshot.
  explicit SnapshotSender(std::uint32_t max_base_age_ticks = 100, std::uint32_t tick_rate_hz = 100)
      : max_base_age_ticks_(max_base_age_ticks), tick_rate_hz_(tick_rate_hz) {}

  // The parts to send for `current` (delta against the acknowledged snapshot if it is
  // still in the history, else full). The parts live in this sender until the next call.
  const std::vector<SnapshotMsg>& encode(const Snapshot& current, Encoding encoding,
                                         std::size_t budget = kMaxPayloadBytes);
  // The same for a snapshot quantized once for all clients (no copy, no re-quantizing).
  // In the steady state (a delta of one part, MessagePack) this allocates nothing: the
  // delta, its parts and the history reuse their storage (fts-wire-bench counts it).
  const std::vector<SnapshotMsg>& encode(SharedSnapshot quantized, Encoding encoding,
                                         std::size_t budget = kMaxPayloadBytes);
  // The snapshot a delta for `current` is made against (nullptr: a full snapshot). Two
  // senders that give the same base (the same shared snapshot: clients of one room) make
  // the same parts for `current`, which RoomSessions::send_snapshot encodes once.
  const Snapshot* base_for(const Snapshot& current) const;
  // `current` went out in parts another sender made for the same base: kept in the
  // history as encode() keeps what it encodes.
  void sent(SharedSnapshot current);
  // The client reports the latest complete snapshot it has.
  void on_ack(std::uint32_t tick);
  std::optional<std::uint32_t> acked_tick() const { return acked_; }
  void reset() {
    for (auto& s : snapshots_) s.reset();
    count_ = next_ = 0;
    acked_.reset();
  }

 private:
  std::uint32_t max_base_age_ticks_;
  std::uint32_t tick_rate_hz_;
  // The last kHistory snapshots sent, a ring: a new one takes the oldest's slot (a vector
  // erased at its front moved all 64 entries per snapshot sent, a host's history per
  // client in cold memory: a quarter of the host's last-level misses, callgrind). The
  // ticks are apart from the snapshots, so the searches (an ack, a base, a resend of a
  // tick) read 256 bytes instead of each snapshot's memory.
  std::size_t slot_of(std::size_t newest) const { return (next_ + kHistory - 1 - newest) % kHistory; }
  void remove(std::size_t newest);  // the `newest`-th newest entry; the newer ones move back
  std::array<std::uint32_t, kHistory> ticks_{};
  std::array<SharedSnapshot, kHistory> snapshots_{};
  std::size_t count_ = 0;  // entries held
  std::size_t next_ = 0;   // the slot the next one takes
  std::optional<std::uint32_t> acked_;
  // Reused storage of the per-client work.
  SnapshotMsg delta_;
  std::vector<BallEntry> motions_;
  std::vector<SnapshotMsg> parts_;
};

// Client side: assembles parts, applies deltas, keeps recent complete snapshots as bases.
class SnapshotReceiver {
 public:
  static constexpr std::size_t kHistory = 64;
  static constexpr std::size_t kMaxPending = 8;

  // Feeds one part. Returns the reconstructed snapshot when this part completes one that
  // is newer than every complete snapshot so far; nullopt while parts are missing.
  Decoded<std::optional<Snapshot>> accept(const SnapshotMsg& part);

  // Tick of the latest complete snapshot (0: none yet): what the client acknowledges.
  std::uint32_t latest_tick() const { return latest_ ? latest_->tick : 0; }
  const Snapshot* latest() const { return latest_ ? &*latest_ : nullptr; }
  // Events of the snapshots accepted so far that were not taken before, each exactly
  // once, in seq order (a delta repeats events while its base lags; a full snapshot
  // repeats the recent window).
  std::vector<Event> take_events();
  void reset() { history_.clear(); pending_.clear(); latest_.reset(); }

 private:
  std::map<std::uint32_t, Snapshot> history_;
  std::map<std::uint32_t, std::vector<std::optional<SnapshotMsg>>> pending_;
  std::optional<Snapshot> latest_;
  std::vector<Event> new_events_;
  std::uint32_t delivered_event_seq_ = 0;
};

}  // namespace fts::protocol
