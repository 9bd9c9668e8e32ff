// A map by id kept as one sorted vector: the part of std::map's interface the match uses
// (find, [], at, count, emplace, erase, iteration in ascending id order), in contiguous
// memory. A room's state is cold when its tick comes (a host steps many rooms), and each
// node of a tree was a cache miss of its own: looking an enemy's Body up in a std::map was
// 8 % of fts-server's CPU at 256 clients, 96 % of that one load (issue 39, 2026-12-07).
// A sorted vector is read in order and prefetched. The core is standard library only
// (ARCHITECTURE.md), so not Boost's flat_map.
// Unlike std::map, an insertion or an erasure moves the elements after it: references and
// iterators into the map do not survive one. The maps here hold tens of entries.
#pragma once

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fts::sim {

template <class K, class V>
class IdMap {
 public:
  using value_type = std::pair<K, V>;
  using iterator = typename std::vector<value_type>::iterator;
  using const_iterator = typename std::vector<value_type>::const_iterator;

  iterator begin() { return items_.begin(); }
  iterator end() { return items_.end(); }
  const_iterator begin() const { return items_.begin(); }
  const_iterator end() const { return items_.end(); }
  std::size_t size() const { return items_.size(); }
  bool empty() const { return items_.empty(); }
  void clear() { items_.clear(); }

  iterator find(const K& k) {
    const auto it = lower(k);
    return it != items_.end() && it->first == k ? it : items_.end();
  }
  const_iterator find(const K& k) const { return const_cast<IdMap*>(this)->find(k); }
  std::size_t count(const K& k) const { return find(k) != end() ? 1 : 0; }

  V& at(const K& k) {
    const auto it = find(k);
    if (it == items_.end()) throw std::out_of_range("IdMap::at: no such id");
    return it->second;
  }
  const V& at(const K& k) const { return const_cast<IdMap*>(this)->at(k); }

  // The value of k, a default one inserted in its place if there was none (a V is made
  // only then: some allocate, a std::deque for one).
  V& operator[](const K& k) {
    const auto it = lower(k);
    if (it != items_.end() && it->first == k) return it->second;
    return items_.insert(it, value_type{k, V{}})->second;
  }

  // Inserts {k, v} unless k is there: the entry of k, and whether it was inserted.
  std::pair<iterator, bool> emplace(const K& k, V v) {
    const auto it = lower(k);
    if (it != items_.end() && it->first == k) return {it, false};
    return {items_.insert(it, value_type{k, std::move(v)}), true};
  }

  iterator erase(const_iterator it) { return items_.erase(it); }
  std::size_t erase(const K& k) {
    const auto it = find(k);
    if (it == items_.end()) return 0;
    items_.erase(it);
    return 1;
  }

  bool operator==(const IdMap&) const = default;

 private:
  iterator lower(const K& k) {
    return std::lower_bound(items_.begin(), items_.end(), k,
                            [](const value_type& e, const K& key) { return e.first < key; });
  }

  std::vector<value_type> items_;
};

}  // namespace fts::sim
