// A drain (SIGTERM under Agones, or the console's drain): no new players or rooms; over
// when the last room ends or the grace time runs out, whichever comes first. Time is
// passed in.
#pragma once

#include <cstdint>
#include <optional>

namespace fts::server {

class Drain {
 public:
  explicit Drain(std::uint32_t grace_ms) : grace_ms_(grace_ms) {}
  void start(std::uint64_t now_ms) {
    if (!started_ms_) started_ms_ = now_ms;
  }
  bool active() const { return started_ms_.has_value(); }
  // Once per tick while active: true from the tick the drain is over on.
  bool over(std::uint64_t now_ms, std::uint32_t rooms) {
    if (!started_ms_) return false;
    if (!over_ms_ && (rooms == 0 || now_ms - *started_ms_ >= grace_ms_)) {
      over_ms_ = now_ms;
      timed_out_ = rooms != 0;
    }
    return over_ms_.has_value();
  }
  bool timed_out() const { return timed_out_; }
  std::optional<std::uint64_t> over_ms() const { return over_ms_; }

 private:
  std::uint32_t grace_ms_;
  std::optional<std::uint64_t> started_ms_;
  std::optional<std::uint64_t> over_ms_;
  bool timed_out_ = false;
};

}  // namespace fts::server
