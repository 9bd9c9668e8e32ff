// fts-wire-bench: encode and decode of snapshot messages (full and delta; 1 player and
// 1 enemy, 8 players and 48 enemies) in both encodings with the field-table codec, plus
// the server's per-client snapshot path. (The old nlohmann-tree codec it replaced was
// timed against it in one run before it was removed: BENCHMARKS.md.)
// Reports ns (Google Benchmark) and bytes (counter "bytes"); never pass/fail.
//
//   build/tests/bench/fts-wire-bench --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "../support/count_allocations.hpp"
#include "../unit/protocol/samples.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/snapshot_delta.hpp"

using namespace fts::protocol;

// Every allocation of the process is counted (tests/support/count_allocations.cpp), so
// that a benchmark can report how many its loop makes per iteration (counter "allocs";
// the goal for the per-client snapshot path is 0 in the steady state).
namespace {

// Allocations per iteration of a benchmark's loop.
struct AllocCount {
  std::uint64_t start = fts::test::allocations_so_far();
  void report(benchmark::State& st) const {
    st.counters["allocs"] = static_cast<double>(fts::test::allocations_so_far() - start) / static_cast<double>(st.iterations());
  }
};

struct Scene {
  const char* name;
  int players, enemies;
};
constexpr Scene kScenes[] = {{"1p1e", 1, 1}, {"8p48e", 8, 48}};

// The message a client gets: full, or the 20 Hz delta (5 ticks at 100 Hz).
SnapshotMsg message_of(const Scene& scene, bool delta) {
  const Snapshot s = test::sample_snapshot(scene.players, scene.enemies);
  if (!delta) return make_snapshot_msg(s, nullptr);
  return make_snapshot_msg(test::advance(s, 5, 0.05), &s);
}

const char* enc_name(Encoding e) { return e == Encoding::json ? "json" : "msgpack"; }

void register_codec(const Scene& scene, bool delta, Encoding enc) {
  const std::string tag = std::string(scene.name) + "/" + (delta ? "delta" : "full") + "/" + enc_name(enc);
  const std::vector<Message> messages{message_of(scene, delta)};

  benchmark::RegisterBenchmark(("encode/" + tag).c_str(), [messages, enc](benchmark::State& st) {
    std::vector<std::uint8_t> out;
    append_payload(enc, messages, out);
    const AllocCount allocs;
    for (auto _ : st) {
      out.clear();
      append_payload(enc, messages, out);
      benchmark::DoNotOptimize(out.data());
    }
    allocs.report(st);
    st.counters["bytes"] = static_cast<double>(out.size());
  });
  const auto bytes = encode_payload(enc, messages);
  benchmark::RegisterBenchmark(("decode/" + tag).c_str(), [bytes, enc](benchmark::State& st) {
    const AllocCount allocs;
    for (auto _ : st) {
      auto d = decode_payload(enc, bytes);
      if (!d.ok()) st.SkipWithError("decode failed");
      benchmark::DoNotOptimize(d);
    }
    allocs.report(st);
    st.counters["bytes"] = static_cast<double>(bytes.size());
  });
}

// What the server does per client and snapshot: the delta against the acknowledged base
// (built from a snapshot quantized once per tick), split, and encoded into a datagram.
void register_sender(const Scene& scene, Encoding enc) {
  const std::string tag = std::string(scene.name) + "/" + enc_name(enc);
  benchmark::RegisterBenchmark(("per_client_delta/" + tag).c_str(), [scene, enc](benchmark::State& st) {
    const Snapshot s0 = test::sample_snapshot(scene.players, scene.enemies);
    const auto q0 = std::make_shared<const Snapshot>(quantize(s0));
    const auto q1 = std::make_shared<const Snapshot>(quantize(test::advance(s0, 5, 0.05)));
    SnapshotSender tx;
    (void)tx.encode(q0, enc);
    tx.on_ack(q0->tick);
    std::vector<std::uint8_t> out;
    Header h;
    h.encoding = enc;
    auto step = [&] {
      // The same tick again: replaces itself in the history.
      for (const auto& p : tx.encode(q1, enc)) {
        out.clear();
        write_header(h, out);
        append_snapshot_payload(enc, p, out);
      }
    };
    step();  // the reused buffers grow to size (two: the delta and its part swap buffers)
    step();
    const AllocCount allocs;
    for (auto _ : st) {
      step();
      benchmark::DoNotOptimize(out.data());
    }
    allocs.report(st);
    st.counters["bytes"] = static_cast<double>(out.size());
  });
}

}  // namespace

int main(int argc, char** argv) {
  for (const auto& scene : kScenes)
    for (bool delta : {false, true})
      for (auto enc : {Encoding::msgpack, Encoding::json}) register_codec(scene, delta, enc);
  for (const auto& scene : kScenes)
    for (auto enc : {Encoding::msgpack, Encoding::json}) register_sender(scene, enc);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
