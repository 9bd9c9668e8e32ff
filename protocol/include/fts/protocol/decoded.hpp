// The result of decoding untrusted bytes: a value or the reason it was rejected.
// (std::expected is C++23; this is the small part of it we need.)
#pragma once

#include <cassert>
#include <utility>
#include <variant>

#include "fts/protocol/reject.hpp"

namespace fts::protocol {

template <class T>
class Decoded {
 public:
  Decoded(T value) : v_(std::move(value)) {}  // NOLINT: implicit on purpose
  Decoded(Reject reason) : v_(reason) {}      // NOLINT

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() { assert(ok()); return std::get<0>(v_); }
  const T& value() const { assert(ok()); return std::get<0>(v_); }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  Reject error() const { assert(!ok()); return std::get<1>(v_); }

 private:
  std::variant<T, Reject> v_;
};

}  // namespace fts::protocol
