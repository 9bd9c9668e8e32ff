// The sessions by session id (SessionTable's index): a hash table in one array, open
// addressing with linear probing. screen() looks every datagram up here, in the serial
// part of a tick; in a std::unordered_map each entry is a node of its own, a cache miss
// per datagram (2.4 % of fts-server's CPU at 256 clients, issue 39). Kept at most half
// full; an erasure moves the entries after it back into the gap (no tombstones), so a
// lookup ends at the first empty slot. Ids are spread by a multiplicative hash (the
// server's are keyed hashes already; tests use small ones).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fts::protocol {

template <class T>
class SessionIdIndex {
 public:
  // The entry of `id`, or nullptr.
  T* find(std::uint32_t id) const {
    if (size_ == 0) return nullptr;
    for (std::size_t i = home(id);; i = next(i)) {
      const Slot& s = slots_[i];
      if (s.value == nullptr) return nullptr;
      if (s.id == id) return s.value;
    }
  }
  std::size_t size() const { return size_; }

  // `id` names `value` (not null) from now on.
  void set(std::uint32_t id, T* value) {
    if ((size_ + 1) * 2 > slots_.size()) grow();
    std::size_t i = home(id);
    while (slots_[i].value != nullptr && slots_[i].id != id) i = next(i);
    if (slots_[i].value == nullptr) ++size_;
    slots_[i] = {id, value};
  }

  // Removes `id`'s entry; whether there was one.
  bool erase(std::uint32_t id) {
    if (size_ == 0) return false;
    std::size_t gap = home(id);
    while (slots_[gap].id != id || slots_[gap].value == nullptr) {
      if (slots_[gap].value == nullptr) return false;
      gap = next(gap);
    }
    // Each later entry of the run moves into the gap unless its home lies cyclically in
    // (gap, j]: there a lookup from its home would not pass the gap.
    for (std::size_t j = next(gap); slots_[j].value != nullptr; j = next(j)) {
      const std::size_t h = home(slots_[j].id);
      const bool stays = gap < j ? (gap < h && h <= j) : (gap < h || h <= j);
      if (stays) continue;
      slots_[gap] = slots_[j];
      gap = j;
    }
    slots_[gap] = {};
    --size_;
    return true;
  }

 private:
  struct Slot {
    std::uint32_t id = 0;
    T* value = nullptr;  // nullptr: empty
  };
  std::size_t home(std::uint32_t id) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull) >> (64 - bits_));
  }
  std::size_t next(std::size_t i) const { return (i + 1) & (slots_.size() - 1); }
  void grow() {
    const std::vector<Slot> old = std::move(slots_);
    bits_ = bits_ == 0 ? 4 : bits_ + 1;
    slots_.assign(std::size_t{1} << bits_, Slot{});
    size_ = 0;
    for (const Slot& s : old)
      if (s.value != nullptr) set(s.id, s.value);
  }

  std::vector<Slot> slots_;
  unsigned bits_ = 0;  // slots_.size() == 2^bits_ (none yet: 0)
  std::size_t size_ = 0;
};

}  // namespace fts::protocol
