// The field tables of the messages (internal): the one place a wire field is named.
// PROTOCOL.md documents the same keys; adding a field is one line here (and one there).
#pragma once

#include <tuple>

#include "fields.hpp"
#include "fts/protocol/messages.hpp"

namespace fts::protocol::wire {

inline constexpr std::uint32_t kU32Max = 0xFFFFFFFFu;
template <class T>
inline constexpr Int<T> kU32{0, kU32Max};
inline constexpr Int<std::int64_t> kCoins{0, kMaxCoins};

// ---- player: one row per PlayerState field, mirrored by PlayerEntry (PROTOCOL.md 8.3)
inline constexpr auto kPlayerSynced = std::make_tuple(
    Synced<PlayerState, PlayerEntry, std::string, Text>{"n", &PlayerEntry::name, &PlayerState::name, {1, kMaxNameBytes}},
    Synced<PlayerState, PlayerEntry, std::int64_t, Int<std::int64_t>>{"c", &PlayerEntry::coins, &PlayerState::coins, kCoins},
    Synced<PlayerState, PlayerEntry, std::int32_t, Int<std::int32_t>>{"l", &PlayerEntry::lives, &PlayerState::lives, {0, 1'000'000}},
    Synced<PlayerState, PlayerEntry, double, Num>{"m", &PlayerEntry::mass, &PlayerState::mass, {0, 1e15}},
    Synced<PlayerState, PlayerEntry, double, Num>{"v", &PlayerEntry::vmax_u_per_s, &PlayerState::vmax_u_per_s, {0, 1e15}},
    Synced<PlayerState, PlayerEntry, double, Num>{"a", &PlayerEntry::accel_u_per_s2, &PlayerState::accel_u_per_s2, {0, 1e15}},
    Synced<PlayerState, PlayerEntry, double, Num>{"x", &PlayerEntry::multiplier, &PlayerState::multiplier, {0, 1e15}},
    Synced<PlayerState, PlayerEntry, bool, Bool>{"b", &PlayerEntry::bank, &PlayerState::bank, {}},
    Synced<PlayerState, PlayerEntry, Weapon, Int<Weapon>>{"w", &PlayerEntry::weapon, &PlayerState::weapon, {0, 1}},
    Synced<PlayerState, PlayerEntry, std::array<std::int64_t, sim::kItemCount>,
           Fixed<std::int64_t, sim::kItemCount, Int<std::int64_t>>>{"p", &PlayerEntry::prices, &PlayerState::prices, {kCoins}},
    Synced<PlayerState, PlayerEntry, bool, Bool>{"r", &PlayerEntry::ready, &PlayerState::ready, {}},
    Synced<PlayerState, PlayerEntry, bool, Bool>{"al", &PlayerEntry::alive, &PlayerState::alive, {}},
    Synced<PlayerState, PlayerEntry, std::uint32_t, Int<std::uint32_t>>{"sp", &PlayerEntry::protected_until_tick, &PlayerState::protected_until_tick, kU32<std::uint32_t>},
    Synced<PlayerState, PlayerEntry, bool, Bool>{"aw", &PlayerEntry::away, &PlayerState::away, {}});

inline constexpr auto kPlayerFields = std::tuple_cat(
    std::make_tuple(Field<PlayerEntry, std::uint32_t, Int<std::uint32_t>>{"i", &PlayerEntry::id, kU32<std::uint32_t>}),
    fields_of(kPlayerSynced));
static_assert(fields::names_every_member<PlayerEntry>(kPlayerFields));
static_assert(fields::names_every_member<PlayerState>(kPlayerSynced, &PlayerState::id));  // id: the entry's "i"

// ---- ball entry, a row (PROTOCOL.md 8.2): a motion entry is the first kBallMotionArity
// A difference of two quantized values, or a position off its prediction (which spans at
// most 4 s: the sender predicts nothing over longer gaps).
inline constexpr std::int64_t kDeltaQ = 16 * kMaxQuantized;
inline constexpr auto kBallRow = std::make_tuple(
    Field<BallEntry, std::uint32_t, Int<std::uint32_t>>{"id", &BallEntry::id, kU32<std::uint32_t>},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"x", &BallEntry::x, {-kDeltaQ, kDeltaQ}},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"y", &BallEntry::y, {-kDeltaQ, kDeltaQ}},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"vx", &BallEntry::vx, {-kDeltaQ, kDeltaQ}},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"vy", &BallEntry::vy, {-kDeltaQ, kDeltaQ}},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"radius", &BallEntry::radius, {0, kMaxQuantized}},
    Field<BallEntry, std::int64_t, Int<std::int64_t>>{"mass", &BallEntry::mass, {0, kMaxQuantized}},
    Field<BallEntry, BallKind, Int<BallKind>>{"kind", &BallEntry::kind, {0, 2}},
    Field<BallEntry, std::uint32_t, Int<std::uint32_t>>{"owner", &BallEntry::owner, kU32<std::uint32_t>});
static_assert(fields::names_every_member<BallEntry>(kBallRow, &BallEntry::full));  // full: the row's length
inline constexpr std::size_t kBallFullArity = std::tuple_size_v<decltype(kBallRow)>;
inline constexpr std::size_t kBallMotionArity = 5;

struct BallKindOfEntry {
  template <class W>
  void put(W& w, const BallEntry& b) const { write_row(w, b, kBallRow, b.full ? kBallFullArity : kBallMotionArity); }
  void get(MsgpackReader& r, BallEntry& b) const {
    const std::size_t n = r.array(kMaxPayloadValues);
    if (r.failed()) return;
    if (n != kBallFullArity && n != kBallMotionArity) return r.fail(Reject::garbage);
    b.full = n == kBallFullArity;
    read_row(r, b, kBallRow, n);
    // A full entry holds values, not differences: half the range.
    if (b.full && (b.x < -kMaxQuantized || b.x > kMaxQuantized || b.y < -kMaxQuantized || b.y > kMaxQuantized ||
                   b.vx < -kMaxQuantized || b.vx > kMaxQuantized || b.vy < -kMaxQuantized || b.vy > kMaxQuantized))
      r.fail(Reject::out_of_range);
  }
};

// "balls": the full entries of SnapshotMsg::balls, one row each (PROTOCOL.md 8.2).
struct FullBalls {
  template <class W>
  void put(W& w, const std::vector<BallEntry>& balls) const {
    std::size_t n = 0;
    for (const auto& b : balls) n += b.full ? 1 : 0;
    w.array(n);
    for (const auto& b : balls)
      if (b.full) BallKindOfEntry{}.put(w, b);
  }
  void get(MsgpackReader& r, std::vector<BallEntry>& balls) const {
    const std::size_t n = r.array(kMaxBallsPerMessage);
    balls.reserve(balls.size() + n);
    for (std::size_t i = 0; i < n && !r.failed(); ++i) {
      BallEntry b;
      BallKindOfEntry{}.get(r, b);
      if (!b.full) return r.fail(Reject::garbage);  // motion entries travel in "mv"
      balls.push_back(b);
    }
  }
};

// "mv": the motion entries of SnapshotMsg::balls (PROTOCOL.md 8.2). MessagePack: one bin
// of Exp-Golomb codes, five streams (id gap, x, y, vx, vy) with one order k each: the id
// gap `id - previous id - 1` as it is (never negative), the others zigzag-mapped. JSON:
// rows [id, x, y, vx, vy]. Either form is read in either encoding; the test vector of
// 8.2.1 holds this code and the document to each other (test_motion_vector.cpp).
struct Motions {
  static constexpr std::size_t kStreams = 5;
  static constexpr unsigned kMaxOrder = 47;
  static constexpr unsigned kCountOrder = 3;

  bool present(const std::vector<BallEntry>& balls) const {
    for (const auto& b : balls)
      if (!b.full) return true;
    return false;
  }
  // The packed form needs ids in increasing order from 1 (each gap >= 0); entries in any
  // other order (make_delta never makes them) are written as rows, which a reader takes.
  static bool packable(const std::vector<BallEntry>& balls) {
    std::uint32_t prev = 0;
    for (const auto& b : balls) {
      if (b.full) continue;
      if (b.id <= prev) return false;
      prev = b.id;
    }
    return true;
  }
  using Codes = std::array<std::uint64_t, kStreams>;
  static Codes codes(const BallEntry& b, std::uint32_t prev) {
    return {std::uint64_t{b.id} - prev - 1, zigzag(b.x), zigzag(b.y), zigzag(b.vx), zigzag(b.vy)};
  }
  // The codes of every motion entry (computed once), the order of each stream that makes
  // it shortest, and the total bits.
  struct Plan {
    std::array<Codes, kMaxBallsPerMessage> fixed;  // no allocation for a valid message
    std::vector<Codes> more;                       // an oversize one (never sent) still encodes
    std::size_t count = 0;
    std::array<unsigned, kStreams> order{};
    std::size_t bits = 0;
    Codes& at(std::size_t i) { return i < fixed.size() ? fixed[i] : more[i - fixed.size()]; }
  };
  static void plan(const std::vector<BallEntry>& balls, Plan& p) {
    std::array<std::uint64_t, kStreams> sum{};
    std::uint32_t prev = 0;
    for (const auto& b : balls) {
      if (b.full) continue;
      if (p.count >= p.fixed.size()) p.more.emplace_back();
      Codes& c = p.at(p.count++);
      c = codes(b, prev);
      for (std::size_t i = 0; i < kStreams; ++i) sum[i] += std::min<std::uint64_t>(c[i], std::uint64_t{1} << 50);
      prev = b.id;
    }
    p.bits = golomb_bits(p.count, kCountOrder) + kStreams * 6;
    for (std::size_t i = 0; i < kStreams; ++i) {
      const unsigned guess = p.count ? static_cast<unsigned>(std::bit_width(sum[i] / p.count)) : 0;
      std::size_t best = SIZE_MAX;
      for (unsigned k = guess > 2 ? guess - 2 : 0; k <= std::min(guess + 1, kMaxOrder); ++k) {
        std::size_t bits = 0;
        for (std::size_t e = 0; e < p.count; ++e) bits += golomb_bits(p.at(e)[i], k);
        if (bits < best) best = bits, p.order[i] = k;
      }
      p.bits += best;
    }
  }
  static void pack(BitWriter& bw, Plan& p) {
    bw.golomb(p.count, kCountOrder);
    for (unsigned k : p.order) bw.bits(k, 6);
    for (std::size_t e = 0; e < p.count; ++e)
      for (std::size_t i = 0; i < kStreams; ++i) bw.golomb(p.at(e)[i], p.order[i]);
  }

  template <class W>
  void put(W& w, const std::vector<BallEntry>& balls) const {
    if (std::is_same_v<W, JsonWriter> || !packable(balls)) {
      std::size_t n = 0;
      for (const auto& b : balls) n += b.full ? 0 : 1;
      w.array(n);
      for (const auto& b : balls)
        if (!b.full) BallKindOfEntry{}.put(w, b);
    } else if constexpr (!std::is_same_v<W, JsonWriter>) {
      Plan p;
      plan(balls, p);
      const std::size_t bytes = (p.bits + 7) / 8;
      if constexpr (std::is_same_v<W, MsgpackWriter>) {
        w.bin_header(bytes);
        BitWriter bw(w.buffer());
        pack(bw, p);
      } else {
        w.bytes += bytes + (bytes <= UINT8_MAX ? 2 : bytes <= UINT16_MAX ? 3 : 5);
      }
    }
  }
  void get(MsgpackReader& r, std::vector<BallEntry>& balls) const {
    if (r.next_is_array()) {
      const std::size_t n = r.array(kMaxBallsPerMessage);
      for (std::size_t i = 0; i < n && !r.failed(); ++i) {
        BallEntry b;
        BallKindOfEntry{}.get(r, b);
        if (b.full) return r.fail(Reject::garbage);
        balls.push_back(b);
      }
      return;
    }
    BitReader br(r.bin(kMaxDatagramBytes));
    if (r.failed()) return;
    const std::uint64_t count = br.golomb(kCountOrder, 16);
    if (count > kMaxBallsPerMessage) return r.fail(Reject::out_of_range);
    std::array<unsigned, kStreams> order{};
    for (auto& k : order)
      if ((k = static_cast<unsigned>(br.bits(6))) > kMaxOrder) return r.fail(Reject::out_of_range);
    std::int64_t prev = 0;
    for (std::uint64_t i = 0; i < count && !br.failed(); ++i) {
      std::array<std::int64_t, kStreams> v{};
      v[0] = static_cast<std::int64_t>(br.golomb(order[0], 50));  // the id gap: no zigzag
      for (std::size_t s = 1; s < kStreams; ++s) v[s] = unzigzag(br.golomb(order[s], 50));
      if (br.failed()) break;  // garbage, below
      BallEntry b;
      b.full = false;
      const std::int64_t id = prev + 1 + v[0];
      if (id > static_cast<std::int64_t>(kU32Max)) return r.fail(Reject::out_of_range);
      for (std::size_t s = 1; s < kStreams; ++s)
        if (v[s] < -kDeltaQ || v[s] > kDeltaQ) return r.fail(Reject::out_of_range);
      b.id = static_cast<std::uint32_t>(id);
      b.x = v[1], b.y = v[2], b.vx = v[3], b.vy = v[4];
      balls.push_back(b);
      prev = id;
    }
    if (br.failed() || !br.rest_is_padding()) r.fail(Reject::garbage);
  }
};

// ---- event, a row (PROTOCOL.md 8.4)
inline constexpr auto kEventRow = std::make_tuple(
    Field<Event, std::uint32_t, Int<std::uint32_t>>{"seq", &Event::seq, {1, kU32Max}},
    Field<Event, std::uint32_t, Int<std::uint32_t>>{"tick", &Event::tick, kU32<std::uint32_t>},
    Field<Event, EventKind, Int<EventKind>>{"kind", &Event::kind, {0, static_cast<int>(EventKind::count_) - 1}},
    Field<Event, std::uint32_t, Int<std::uint32_t>>{"a", &Event::a, kU32<std::uint32_t>},
    Field<Event, std::uint32_t, Int<std::uint32_t>>{"b", &Event::b, kU32<std::uint32_t>},
    Field<Event, std::int64_t, Int<std::int64_t>>{"value", &Event::value, {-kMaxCoins, kMaxCoins}});
static_assert(fields::names_every_member<Event>(kEventRow));

template <class M, class Table>
struct RowOf {
  const Table* table;
  // The last `optional_tail` fields may be left off: written only when one of them is not
  // its default, read when the row has them (an input frame's tick, PROTOCOL.md 4.5).
  std::size_t optional_tail = 0;
  template <class W>
  void put(W& w, const M& m) const {
    constexpr std::size_t n = std::tuple_size_v<Table>;
    std::size_t arity = n, index = 0, last_set = 0;
    std::apply([&](const auto&... f) { ((++index, last_set = f.of(m) == std::decay_t<decltype(f.of(m))>{} ? last_set : index), ...); },
               *table);
    if (optional_tail > 0) arity = std::max(n - optional_tail, last_set);
    write_row(w, m, *table, arity);
  }
  void get(MsgpackReader& r, M& m) const {
    constexpr std::size_t n = std::tuple_size_v<Table>;
    const std::size_t got = r.array(kMaxPayloadValues);
    if ((got > n || got + optional_tail < n) && !r.failed()) return r.fail(Reject::garbage);
    read_row(r, m, *table, got);
  }
};

template <class M, class Table>
struct MapOf {
  const Table* table;
  template <class W>
  void put(W& w, const M& m) const { write_map(w, nullptr, m, *table); }
  void get(MsgpackReader& r, M& m) const { read_map(r, m, *table); }
};

inline constexpr MapOf<PlayerEntry, decltype(kPlayerFields)> kPlayerMap{&kPlayerFields};

// ---- board (PROTOCOL.md 4.7c): a leaderboard, its rows [rank, name, level, coins]
inline constexpr auto kBoardRow = std::make_tuple(
    Field<BoardRow, std::uint32_t, Int<std::uint32_t>>{"rank", &BoardRow::rank, {1, kU32Max}},
    Field<BoardRow, std::string, Text>{"name", &BoardRow::name, {1, kMaxNameBytes}},
    Field<BoardRow, std::int64_t, Int<std::int64_t>>{"level", &BoardRow::level, {0, 1'000'000}},
    Field<BoardRow, std::int64_t, Int<std::int64_t>>{"coins", &BoardRow::coins, kCoins});
static_assert(fields::names_every_member<BoardRow>(kBoardRow));

inline constexpr auto kLeaderboardFields = std::make_tuple(
    Field<Leaderboard, std::uint32_t, Int<std::uint32_t>>{"cmd", &Leaderboard::cmd, {1, kU32Max}},
    Field<Leaderboard, std::vector<BoardRow>, List<BoardRow, RowOf<BoardRow, decltype(kBoardRow)>>>{
        "top", &Leaderboard::top, {kBoardRows, {&kBoardRow}}},
    Field<Leaderboard, std::uint32_t, Int<std::uint32_t>>{"of", &Leaderboard::of, kU32<std::uint32_t>},
    Field<Leaderboard, std::uint32_t, Int<std::uint32_t>>{"rank", &Leaderboard::rank, kU32<std::uint32_t>, Presence::nonzero},
    Field<Leaderboard, std::int64_t, Int<std::int64_t>>{"best", &Leaderboard::best, {0, 1'000'000}, Presence::nonzero},
    Field<Leaderboard, std::int64_t, Int<std::int64_t>>{"best_coins", &Leaderboard::best_coins, kCoins, Presence::nonzero});

// ---- snap (PROTOCOL.md 4.10)
inline constexpr auto kSnapFields = std::make_tuple(
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"tick", &SnapshotMsg::tick, kU32<std::uint32_t>},
    Field<SnapshotMsg, std::optional<std::uint32_t>, Int<std::uint32_t>>{"base", &SnapshotMsg::base, kU32<std::uint32_t>, Presence::optional},
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"part", &SnapshotMsg::part, {0, kMaxSnapshotParts}},
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"parts", &SnapshotMsg::parts, {0, kMaxSnapshotParts}},
    Field<SnapshotMsg, Phase, Named<Phase, 4>>{"phase", &SnapshotMsg::phase, {{"lobby", "play", "shop", "over"}}},
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"level", &SnapshotMsg::level, {0, 1'000'000}},
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"dl", &SnapshotMsg::deadline_tick, kU32<std::uint32_t>, Presence::nonzero},
    Field<SnapshotMsg, std::uint32_t, Int<std::uint32_t>>{"hz", &SnapshotMsg::tick_rate_hz, {0, kMaxTickRateHz}, Presence::nonzero},
    Field<SnapshotMsg, std::vector<BallEntry>, FullBalls>{"balls", &SnapshotMsg::balls, {}},
    Field<SnapshotMsg, std::vector<BallEntry>, Motions>{"mv", &SnapshotMsg::balls, {}, Presence::nonzero},
    Field<SnapshotMsg, std::vector<std::uint32_t>, List<std::uint32_t, Int<std::uint32_t>>>{"gone", &SnapshotMsg::gone, {kMaxBallsPerMessage, kU32<std::uint32_t>}, Presence::nonzero},
    Field<SnapshotMsg, std::vector<PlayerEntry>, List<PlayerEntry, MapOf<PlayerEntry, decltype(kPlayerFields)>>>{"players", &SnapshotMsg::players, {kMaxPlayersPerMessage, kPlayerMap}},
    Field<SnapshotMsg, std::vector<std::uint32_t>, List<std::uint32_t, Int<std::uint32_t>>>{"left", &SnapshotMsg::left, {kMaxPlayersPerMessage, kU32<std::uint32_t>}, Presence::nonzero},
    Field<SnapshotMsg, std::vector<Event>, List<Event, RowOf<Event, decltype(kEventRow)>>>{"events", &SnapshotMsg::events, {kMaxEventsPerMessage, {&kEventRow}}, Presence::nonzero});

// ---- input (PROTOCOL.md 4.5)
inline constexpr auto kInputFrameRow = std::make_tuple(
    Field<InputFrame, std::uint32_t, Int<std::uint32_t>>{"seq", &InputFrame::seq, kU32<std::uint32_t>},
    Field<InputFrame, std::int8_t, Int<std::int8_t>>{"move_x", &InputFrame::move_x, {-1, 1}},
    Field<InputFrame, std::int8_t, Int<std::int8_t>>{"move_y", &InputFrame::move_y, {-1, 1}},
    Field<InputFrame, bool, Bit>{"fire", &InputFrame::fire, {}},
    Field<InputFrame, std::uint32_t, Int<std::uint32_t>>{"tick", &InputFrame::tick, kU32<std::uint32_t>});
static_assert(fields::names_every_member<InputFrame>(kInputFrameRow));

inline constexpr auto kInputFields = std::make_tuple(
    Field<Input, std::uint32_t, Int<std::uint32_t>>{"ack", &Input::snapshot_ack, kU32<std::uint32_t>},
    Field<Input, std::vector<InputFrame>, List<InputFrame, RowOf<InputFrame, decltype(kInputFrameRow)>>>{"f", &Input::frames, {kMaxInputFrames, {&kInputFrameRow, 1}}});

// Checks across fields, after a table read.
inline void check(MsgpackReader& r, const SnapshotMsg& m) {
  if (r.failed()) return;
  if (m.base && *m.base >= m.tick) return r.fail(Reject::out_of_range);
  if (m.parts == 0 || m.part >= m.parts) return r.fail(Reject::out_of_range);
  if (m.balls.size() > kMaxBallsPerMessage) return r.fail(Reject::out_of_range);
  if (m.base && m.tick_rate_hz && m.tick - *m.base > kMaxPredictionTicks) return r.fail(Reject::out_of_range);
  if (!m.base)
    for (const auto& b : m.balls)
      if (!b.full) return r.fail(Reject::out_of_range);  // a full snapshot needs full entries
}

}  // namespace fts::protocol::wire
