#include "app/worker_pool.hpp"

#include <sched.h>

#include <chrono>
#include <utility>

namespace fts::server {

unsigned WorkerPool::usable_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int n = CPU_COUNT(&set);
    if (n > 0) return static_cast<unsigned>(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? hw : 1;
}

WorkerPool::WorkerPool(unsigned threads) {
  if (threads == 0) threads = usable_cores();
  done_.assign(threads, 0);
  shares_ = std::make_unique<Share[]>(threads);
  workers_.reserve(threads - 1);
  for (std::size_t slot = 1; slot < threads; ++slot) workers_.emplace_back([this, slot] { work(slot); });
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mu_);
    stop_ = true;
  }
  start_cv_.notify_all();
  for (auto& t : workers_) t.join();
}

// Takes indices until none is left and runs them, its own share first, then the others'
// in turn; how many it ran. The first exception is kept for run().
std::uint64_t WorkerPool::claim(std::size_t slot) {
  std::uint64_t ran = 0;
  const std::size_t threads = done_.size();
  for (std::size_t k = 0; k < threads; ++k) {
    Share& share = shares_[(slot + k) % threads];
    for (std::size_t i = share.next.fetch_add(1, std::memory_order_relaxed); i < share.end;
         i = share.next.fetch_add(1, std::memory_order_relaxed)) {
      ++ran;
      try {
        (*job_)(i, slot);
      } catch (...) {
        std::lock_guard lock(mu_);
        if (!error_) error_ = std::current_exception();
      }
    }
  }
  return ran;
}

// A worker joins a run only if it wakes while the run is on (job_ set): the caller never
// waits for a worker that was not scheduled in time, only for those inside claim().
void WorkerPool::work(std::size_t slot) {
  std::uint64_t seen = 0;
  std::unique_lock lock(mu_, std::defer_lock);
  for (;;) {
    // The next phase of a tick follows within microseconds: spin that long before sleeping,
    // since waking a sleeping thread costs more than a phase's work on a busy host.
    const auto until = std::chrono::steady_clock::now() + kSpin;
    while (published_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < until)
      std::this_thread::yield();
    lock.lock();
    start_cv_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    if (job_ == nullptr) {  // that run is over already
      lock.unlock();
      continue;
    }
    ++active_;
    lock.unlock();
    const std::uint64_t ran = claim(slot);
    lock.lock();
    done_[slot] += ran;
    finished_ += ran;
    --active_;
    if (finished_ == n_ && active_ == 0) done_cv_.notify_one();
    lock.unlock();
  }
}

void WorkerPool::run(std::size_t n, const Job& job) {
  if (n == 0) return;
  if (workers_.empty() || n == 1) {  // nothing to share: no wake-up, no join
    for (std::size_t i = 0; i < n; ++i) job(i, 0);
    std::lock_guard lock(mu_);
    done_[0] += n;
    return;
  }
  {
    std::lock_guard lock(mu_);
    job_ = &job;
    n_ = n;
    const std::size_t threads = done_.size();
    for (std::size_t k = 0; k < threads; ++k) {
      shares_[k].next.store(k * n / threads, std::memory_order_relaxed);
      shares_[k].end = (k + 1) * n / threads;
    }
    finished_ = 0;
    error_ = nullptr;
    published_.store(++generation_, std::memory_order_release);
  }
  start_cv_.notify_all();
  const std::uint64_t ran = claim(0);
  std::exception_ptr error;
  {
    std::unique_lock lock(mu_);
    done_[0] += ran;
    finished_ += ran;
    // The workers' last jobs end within microseconds of the caller's: it waits that long
    // awake (as a worker spins for the next run) before it sleeps, since a wake-up from
    // the condition variable costs more than a phase's last job on a busy host.
    const auto until = std::chrono::steady_clock::now() + kSpin;
    while (!(finished_ == n_ && active_ == 0) && std::chrono::steady_clock::now() < until) {
      lock.unlock();
      std::this_thread::yield();
      lock.lock();
    }
    done_cv_.wait(lock, [&] { return finished_ == n_ && active_ == 0; });
    job_ = nullptr;
    error = std::exchange(error_, nullptr);
  }
  if (error) std::rethrow_exception(error);
}

std::vector<std::uint64_t> WorkerPool::jobs_per_thread() const {
  std::lock_guard lock(mu_);
  return done_;
}

}  // namespace fts::server
