#include "fleet/agones_sync.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace fts::server {
namespace {

SdkCall post(SdkOp op, const std::string& path) { return SdkCall{op, "POST", path, "{}", {}, {}, 0, std::nullopt}; }

// int64 fields travel as JSON strings in the gateway's mapping, as the docs show.
std::string int64_json(const char* field, std::uint64_t v) { return nlohmann::json{{field, std::to_string(v)}}.dump(); }

// Kubernetes label values: up to 63 of [A-Za-z0-9._-], starting and ending alphanumeric.
std::string label_value(const std::string& v) {
  std::string out;
  for (char c : v) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == '-';
    out += ok ? c : '-';
  }
  if (out.size() > 63) out.resize(63);
  while (!out.empty() && !std::isalnum(static_cast<unsigned char>(out.back()))) out.pop_back();
  while (!out.empty() && !std::isalnum(static_cast<unsigned char>(out.front()))) out.erase(out.begin());
  return out.empty() ? "none" : out;
}

SdkCall list_value_call(SdkOp op, const char* list, const std::string& value) {
  const char* verb = op == SdkOp::list_add ? ":addValue" : ":removeValue";
  return SdkCall{op, "POST", std::string("/v1beta1/lists/") + list + verb, nlohmann::json{{"value", value}}.dump(),
                 list, value, 0, std::nullopt};
}

// The first call that brings List `list` from `held` (what the sidecar holds) to the
// first `capacity` distinct values of `wanted`, in its order: removals before additions,
// so the List never holds more than `capacity` values on the way.
template <class Values>
std::optional<SdkCall> list_call(const char* list, const std::set<std::string>& held, const Values& wanted,
                                 std::uint64_t capacity) {
  std::set<std::string_view, std::less<>> target;
  std::vector<const std::string*> order;
  for (const std::string& v : wanted) {
    if (order.size() >= capacity) break;
    if (target.insert(v).second) order.push_back(&v);
  }
  for (const auto& v : held)
    if (!target.count(v)) return list_value_call(SdkOp::list_remove, list, v);
  for (const auto* v : order)
    if (!held.count(*v)) return list_value_call(SdkOp::list_add, list, *v);
  return std::nullopt;
}

}  // namespace

AgonesCapacity agones_capacity(std::uint32_t max_rooms, std::uint32_t max_players) {
  AgonesCapacity c;
  c.seats = kFleetNames[kSeatsRow].capacity(max_rooms, max_players);
  c.rooms = static_cast<std::uint32_t>(kFleetNames[kRoomsRow].capacity(max_rooms, max_players));
  c.players = static_cast<std::uint32_t>(kFleetNames[kPlayersRow].capacity(max_rooms, max_players));
  return c;
}

AgonesSync::AgonesSync(std::uint32_t update_retry_min_ms, std::uint32_t update_retry_max_ms) {
  retry_.fill(UpdateRetry(update_retry_min_ms, update_retry_max_ms));
}

std::optional<SdkCall> AgonesSync::next(const AgonesWanted& w, std::uint64_t now_ms) const {
  const auto due = [&](std::size_t row) { return retry_[row].due(now_ms); };
  const char* seats_counter = kFleetNames[kSeatsRow].name;
  const auto counter_call = [&](SdkOp op, const char* field, std::uint64_t v) {
    return SdkCall{op, "PATCH", std::string("/v1beta1/counters/") + seats_counter, int64_json(field, v), seats_counter,
                   {}, v, kSeatsRow};
  };
  // Capacities first: the allocator must never see this server Ready with the manifest's
  // numbers if the server's own limits differ (unless the sidecar will not take them).
  if (due(kSeatsRow) && seats_capacity_ != w.capacity.seats)
    return counter_call(SdkOp::counter_capacity, "capacity", w.capacity.seats);
  for (const auto& [row, cap] : {std::pair{kRoomsRow, w.capacity.rooms}, std::pair{kPlayersRow, w.capacity.players}}) {
    const char* list = kFleetNames[row].name;
    const auto it = list_capacity_.find(list);
    if (!due(row) || (it != list_capacity_.end() && it->second == cap)) continue;
    // Only the fields in the body change (the gateway's field mask): the values stay.
    return SdkCall{SdkOp::list_capacity, "PATCH", std::string("/v1beta1/lists/") + list, int64_json("capacity", cap),
                   list, {}, cap, row};
  }
  if (w.ready && !ready_) return post(SdkOp::ready, "/ready");
  if (w.health_seq != health_seq_) {
    SdkCall c = post(SdkOp::health, "/health");
    c.number = w.health_seq;
    return c;
  }
  const std::map<std::string, std::string> labels = {{"phase", label_value(w.state.phase)},
                                                      {"version", label_value(w.version)}};
  for (const auto& [key, value] : labels) {
    const auto it = labels_.find(key);
    if (it != labels_.end() && it->second == value) continue;
    SdkCall c{SdkOp::label, "PUT", "/metadata/label", nlohmann::json{{"key", key}, {"value", value}}.dump(), key,
              value, 0, std::nullopt};
    return c;
  }
  const std::uint64_t seats = std::min<std::uint64_t>(w.state.seats, w.capacity.seats);
  if (due(kSeatsRow) && seats_ != seats) return counter_call(SdkOp::counter, "count", seats);
  const auto held = [&](const char* list) -> const std::set<std::string>& {
    static const std::set<std::string> none;
    const auto it = lists_.find(list);
    return it == lists_.end() ? none : it->second;
  };
  const auto list_update = [&](std::size_t row, const auto& wanted, std::uint64_t cap) -> std::optional<SdkCall> {
    if (!due(row)) return std::nullopt;
    const char* list = kFleetNames[row].name;
    auto c = list_call(list, held(list), wanted, cap);
    if (c) c->row = row;
    return c;
  };
  if (auto c = list_update(kRoomsRow, w.state.room_codes, w.capacity.rooms)) return c;
  if (auto c = list_update(kPlayersRow, w.state.players, w.capacity.players)) return c;
  if (w.shutdown && !shutdown_) return post(SdkOp::shutdown, "/shutdown");
  return std::nullopt;
}

bool AgonesSync::failed(const SdkCall& c, std::uint64_t now_ms) {
  if (!c.row) return false;
  return retry_.at(*c.row).failed(now_ms);
}

std::optional<std::uint64_t> AgonesSync::next_retry_ms(std::uint64_t now_ms) const {
  std::optional<std::uint64_t> first;
  for (const auto& r : retry_)
    if (r.failing() && r.next_ms() > now_ms && (!first || r.next_ms() < *first)) first = r.next_ms();
  return first;
}

void AgonesSync::done(const SdkCall& c) {
  if (c.row) retry_.at(*c.row).succeeded();
  switch (c.op) {
    case SdkOp::counter_capacity: seats_capacity_ = c.number; break;
    case SdkOp::list_capacity: list_capacity_[c.key] = c.number; break;
    case SdkOp::ready: ready_ = true; break;
    case SdkOp::health: health_seq_ = c.number; break;
    case SdkOp::label: labels_[c.key] = c.value; break;
    case SdkOp::counter: seats_ = c.number; break;
    case SdkOp::list_remove: lists_[c.key].erase(c.value); break;
    case SdkOp::list_add: lists_[c.key].insert(c.value); break;
    case SdkOp::shutdown: shutdown_ = true; break;
  }
}

}  // namespace fts::server
