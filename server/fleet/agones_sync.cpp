#include "fleet/agones_sync.hpp"

#include <cctype>

#include <nlohmann/json.hpp>

namespace fts::server {
namespace {

SdkCall post(SdkOp op, const std::string& path) { return SdkCall{op, "POST", path, "{}", {}, {}, 0}; }

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

}  // namespace

std::optional<SdkCall> AgonesSync::next(const AgonesWanted& w) const {
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
              value, 0};
    return c;
  }
  if (!rooms_ || *rooms_ != w.state.rooms) {
    // int64 fields travel as JSON strings in the gateway's mapping, as the docs show.
    SdkCall c{SdkOp::counter, "PATCH", std::string("/v1beta1/counters/") + kRoomsCounter,
              nlohmann::json{{"count", std::to_string(w.state.rooms)}}.dump(), {}, {}, w.state.rooms};
    return c;
  }
  for (const auto& name : players_) {
    if (w.state.players.count(name)) continue;
    return SdkCall{SdkOp::list_remove, "POST", std::string("/v1beta1/lists/") + kPlayersList + ":removeValue",
                   nlohmann::json{{"value", name}}.dump(), {}, name, 0};
  }
  for (const auto& name : w.state.players) {
    if (players_.count(name)) continue;
    return SdkCall{SdkOp::list_add, "POST", std::string("/v1beta1/lists/") + kPlayersList + ":addValue",
                   nlohmann::json{{"value", name}}.dump(), {}, name, 0};
  }
  if (w.shutdown && !shutdown_) return post(SdkOp::shutdown, "/shutdown");
  return std::nullopt;
}

void AgonesSync::done(const SdkCall& c) {
  switch (c.op) {
    case SdkOp::ready: ready_ = true; break;
    case SdkOp::health: health_seq_ = c.number; break;
    case SdkOp::label: labels_[c.key] = c.value; break;
    case SdkOp::counter: rooms_ = c.number; break;
    case SdkOp::list_remove: players_.erase(c.value); break;
    case SdkOp::list_add: players_.insert(c.value); break;
    case SdkOp::shutdown: shutdown_ = true; break;
  }
}

}  // namespace fts::server
