// sim::IdMap: the sorted vector that holds a match's bodies by id (fts/sim/id_map.hpp).
#include <catch2/catch.hpp>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "fts/sim/id_map.hpp"
#include "fts/sim/rng.hpp"

using fts::sim::IdMap;

TEST_CASE("IdMap: finds, inserts, erases and iterates as a std::map of the same operations does",
          "[match][id_map]") {
  // A seeded walk of random operations on both; after each, the same entries in the same order.
  IdMap<int, std::string> flat;
  std::map<int, std::string> tree;
  fts::sim::Rng rng(39);
  for (int step = 0; step < 2000; ++step) {
    const int key = static_cast<int>(rng.uniform_int(0, 39));
    const int op = static_cast<int>(rng.uniform_int(0, 4));
    if (op == 0) {
      flat[key] += "a";
      tree[key] += "a";
    } else if (op == 1) {
      const auto [it, inserted] = flat.emplace(key, std::to_string(step));
      const auto [jt, jinserted] = tree.emplace(key, std::to_string(step));
      REQUIRE(inserted == jinserted);
      REQUIRE(it->second == jt->second);
    } else if (op == 2) {
      REQUIRE(flat.erase(key) == tree.erase(key));
    } else if (op == 3) {
      const auto it = flat.find(key);
      REQUIRE((it == flat.end()) == (tree.count(key) == 0));
      if (it != flat.end()) flat.erase(it), tree.erase(key);
    } else {
      REQUIRE(flat.count(key) == tree.count(key));
    }
    REQUIRE(flat.size() == tree.size());
    auto jt = tree.begin();
    for (const auto& [id, value] : flat) {
      REQUIRE(id == jt->first);
      REQUIRE(value == jt->second);
      ++jt;
    }
  }
}

TEST_CASE("IdMap: at() throws for a missing id and changes nothing, and == compares entries", "[match][id_map]") {
  IdMap<unsigned, int> m;
  m[7] = 70;
  m[3] = 30;
  CHECK(m.at(3) == 30);
  CHECK_THROWS_AS(m.at(5), std::out_of_range);
  CHECK(m.size() == 2);
  const IdMap<unsigned, int>& c = m;
  CHECK(c.find(5) == c.end());
  CHECK(c.at(7) == 70);
  IdMap<unsigned, int> other;
  other.emplace(3, 30);
  other.emplace(7, 70);
  CHECK(other == m);
  other[7] = 71;
  CHECK_FALSE(other == m);
  std::vector<unsigned> order;
  for (const auto& [id, v] : m) order.push_back(id);
  CHECK(order == std::vector<unsigned>{3, 7});
}

namespace {
int made = 0;  // default constructions of Counted
struct Counted {
  Counted() { ++made; }
  int value = 0;
};
}  // namespace

TEST_CASE("IdMap: [] makes a value only for a missing id", "[match][id_map]") {
  // A room looks its held inputs up with [] per datagram; a default Held holds a
  // std::deque, which allocates when made.
  IdMap<int, Counted> m;
  m[4].value = 1;
  CHECK(made == 1);
  for (int i = 0; i < 10; ++i) m[4].value += 1;
  CHECK(made == 1);
  CHECK(m.at(4).value == 11);
  m[2];
  CHECK(made == 2);
}
