// Fork-join over the rooms (issue 29): run(n, job) calls job(i, slot) once for every i
// in [0, n), spread over the pool's threads (the caller is one of them), and returns when
// every call has returned. With one thread it is a plain loop on the caller. `slot` is
// the thread running the call (0 the caller, below threads()): a job that needs scratch
// takes its slot's from an array its owner keeps, one per thread (no thread_local).
//
// What it guarantees: run() returning happens-after every job(i) (the join takes the
// pool's mutex), and job(i) happens-after everything the caller did before run(); the
// caller waits for the jobs, never for a worker that did not wake in time (it then runs
// the jobs itself: an overloaded machine costs speed, not a stall). A
// room's state is therefore touched by one thread at a time, and which thread that is
// changes nothing a room computes: each index is claimed from an atomic cursor, a
// thread's own share of the indices first, then what is left of the others' (so a room
// keeps to one thread while the threads keep pace, and the rooms still spread over the
// threads by their cost when they do not).
// The jobs must not touch what another index's job touches; they may throw: the first
// exception is rethrown by run() on the caller once every job has finished.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace fts::server {

class WorkerPool {
 public:
  using Job = std::function<void(std::size_t i, std::size_t slot)>;
  // `threads` counts the caller: 1 starts no thread. 0 means every core the process may use.
  explicit WorkerPool(unsigned threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }
  void run(std::size_t n, const Job& job);
  // Jobs each thread ran since the start, the caller first (for the stats line).
  std::vector<std::uint64_t> jobs_per_thread() const;

  // The cores this process may run on (sched_getaffinity; at least 1).
  static unsigned usable_cores();

 private:
  void work(std::size_t slot);
  std::uint64_t claim(std::size_t slot);

  mutable std::mutex mu_;
  std::condition_variable start_cv_, done_cv_;
  const Job* job_ = nullptr;
  std::size_t n_ = 0;
  // Each thread's share of a run's indices (slot k: [k n / T, (k + 1) n / T)), taken from
  // the front by its own thread first, then by any thread whose share is done: a room's
  // jobs (its timers, its step, its snapshots) fall to the same thread phase after phase
  // and tick after tick while the threads keep pace, so its state stays in that core's
  // caches. Each on a cache line of its own.
  struct alignas(64) Share {
    std::atomic<std::size_t> next{0};
    std::size_t end = 0;
  };
  std::unique_ptr<Share[]> shares_;
  std::uint64_t generation_ = 0;  // one per run(): a worker joins each run at most once
  std::atomic<std::uint64_t> published_{0};  // generation_, read without the lock while spinning
  // How long a worker that finished a run spins for the next before it sleeps (a tick's
  // phases follow each other closely; between ticks it sleeps): at most 3 x this per tick
  // of one core per worker. The caller, its share done, waits as long awake for the
  // workers' last jobs before it sleeps: a wake-up through the condition variable cost
  // more than that (fts-host-bench, 2 / 1 threads' tick 0.85-0.87 -> 0.67-0.77 at 1024 and
  // 2048 clients, and less CPU: 2026-12-07-lookups/).
  static constexpr std::chrono::microseconds kSpin{100};
  std::size_t finished_ = 0;      // jobs of the current run done
  unsigned active_ = 0;           // workers inside the current run's claim()
  bool stop_ = false;
  std::exception_ptr error_;
  std::vector<std::uint64_t> done_;  // per slot, guarded by mu_ (added to at the join)
  std::vector<std::thread> workers_;
};

}  // namespace fts::server
