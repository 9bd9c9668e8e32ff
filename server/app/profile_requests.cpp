#include "app/profile_requests.hpp"

#include <algorithm>

#include "app/chat_relay.hpp"
#include "fts/protocol/constants.hpp"

namespace fts::server {

using protocol::ResultCode;

std::string board_name(const std::string& raw) {
  std::string name = ChatRelay::clean(raw, protocol::kMaxNameBytes);
  return name.empty() ? std::string("?") : name;
}

namespace {

std::int64_t level_of(std::int64_t v) { return std::clamp<std::int64_t>(v, 0, 1'000'000); }
std::int64_t coins_of(std::int64_t v) { return std::clamp<std::int64_t>(v, 0, protocol::kMaxCoins); }
std::uint32_t u32_of(std::int64_t v) { return static_cast<std::uint32_t>(std::clamp<std::int64_t>(v, 0, 0xFFFFFFFF)); }

}  // namespace

protocol::Leaderboard read_board(profiles::Store& store, BoardCache& cache, std::uint64_t generation,
                                 const std::string& fingerprint) {
  if (!cache.valid || cache.generation != generation) {
    cache.top.clear();
    std::uint32_t rank = 0;
    for (const auto& p : store.top(profiles::Board::level, protocol::kBoardRows))
      cache.top.push_back({++rank, board_name(p.name), level_of(p.best_level), coins_of(p.best_level_coins)});
    cache.of = u32_of(store.ranked());
    cache.generation = generation;
    cache.valid = true;
  }
  protocol::Leaderboard b;
  b.top = cache.top;
  b.of = cache.of;
  if (!fingerprint.empty()) {
    if (const auto p = store.profile(fingerprint); p && p->matches > 0) {
      b.rank = u32_of(store.rank(profiles::Board::level, fingerprint));
      b.best = level_of(p->best_level);
      b.best_coins = coins_of(p->best_level_coins);
    }
  }
  return b;
}

ProfileRequests::ProfileRequests() : shared_(std::make_shared<Shared>()) {}

bool ProfileRequests::may_ask(std::uint32_t player, std::uint64_t now_ms) {
  if (in_flight_.count(player) > 0) return false;
  auto [it, fresh] = last_ask_ms_.try_emplace(player, now_ms);
  if (!fresh && now_ms < it->second + kMinIntervalMs) return false;
  it->second = now_ms;
  return true;
}

std::uint64_t ProfileRequests::begin(std::uint32_t player, std::uint32_t rid) {
  in_flight_[player] = {rid, ++serial_};
  return serial_;
}

void ProfileRequests::top(profiles::Writer& writer, std::uint32_t player, std::uint32_t rid,
                          const std::string& fingerprint) {
  const std::uint64_t serial = begin(player, rid);
  profiles::Writer* w = &writer;  // the job runs on its thread, while it lives
  writer.query([shared = shared_, w, player, rid, serial, fingerprint](profiles::Store* store) {
    ProfileAnswer a{player, rid, serial, ResultCode::ok, "", std::nullopt};
    if (!store) {
      a.code = ResultCode::unavailable;
      a.message = std::string(protocol::result_sentence(a.code));
    } else {
      try {
        a.board = read_board(*store, shared->cache, w->stats().committed, fingerprint);
        a.board->cmd = rid;
      } catch (const std::exception&) {
        shared->cache.valid = false;
        a.code = ResultCode::unavailable;
        a.message = std::string(protocol::result_sentence(a.code));
        a.board.reset();
      }
    }
    std::lock_guard lock(shared->mu);
    shared->answers.push_back(std::move(a));
  });
}

bool ProfileRequests::forget(profiles::Writer& writer, std::uint32_t player, std::uint32_t rid,
                             const std::string& fingerprint) {
  if (!writer.push(profiles::Forget{fingerprint})) return false;
  const std::uint64_t serial = begin(player, rid);
  // Asked after the push: the writer tries the erasure first (Writer::query).
  writer.query([shared = shared_, player, rid, serial, fingerprint](profiles::Store* store) {
    ProfileAnswer a{player, rid, serial, ResultCode::ok, "", std::nullopt};
    bool gone = false;
    if (store) {
      try {
        gone = !store->profile(fingerprint).has_value();
      } catch (const std::exception&) {
      }
    }
    a.message = gone ? "your profile is erased: its records are gone from this server"
                     : "your profile will be erased: the database does not answer now, and the server keeps the "
                       "erasure until it does";
    std::lock_guard lock(shared->mu);
    shared->answers.push_back(std::move(a));
  });
  return true;
}

std::vector<ProfileAnswer> ProfileRequests::take() {
  std::vector<ProfileAnswer> got;
  {
    std::lock_guard lock(shared_->mu);
    got.swap(shared_->answers);
  }
  std::vector<ProfileAnswer> out;
  for (auto& a : got) {
    auto it = in_flight_.find(a.player);
    if (it == in_flight_.end() || it->second.serial != a.serial) continue;  // its session is gone
    in_flight_.erase(it);
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace fts::server
