// What the libFuzzer targets share: a property that must hold (else the input is a
// finding: the message on stderr, then abort, which libFuzzer saves as crash-*).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace fts::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz property failed: %s\n", what.c_str());
  std::abort();
}

inline void check(bool ok, const char* what) {
  if (!ok) fail(what);
}

}  // namespace fts::fuzz
