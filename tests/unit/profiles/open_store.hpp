// Opens a profile store for a test, or fails the test with the store's error.
#pragma once

#include <catch2/catch.hpp>
#include <memory>
#include <string>

#include "profiles/store.hpp"

namespace fts::test {

inline std::unique_ptr<profiles::Store> open_ok(const std::string& url) {
  auto r = profiles::Store::open(url);
  if (auto* e = std::get_if<std::string>(&r)) FAIL("open: " << *e);
  return std::move(std::get<std::unique_ptr<profiles::Store>>(r));
}

}  // namespace fts::test
