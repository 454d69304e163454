#include "bodies/threads.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace rancf {

namespace {

std::atomic<int> g_threads{1};

/// The workers and the one loop they share at a time (threads.hpp).  Never destroyed: its
/// threads are detached and wait on cv_ until the process ends.
class Pool {
 public:
  bool run(int n, void (*job)(void*, int), void* ctx) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    grow(std::min(n, g_threads.load()) - 1);
    if (started_ == 0) return false;
    {
      const std::lock_guard<std::mutex> lk(mu_);
      job_ = job;
      ctx_ = ctx;
      n_ = n;
      next_.store(1);
      done_.store(0);
      open_ = true;
      ++gen_;
    }
    cv_.notify_all();
    job(ctx, 0);
    take(job, ctx, n);
    while (done_.load(std::memory_order_acquire) < n - 1) std::this_thread::yield();
    std::unique_lock<std::mutex> lk(mu_);
    open_ = false;
    idle_.wait(lk, [this] { return active_ == 0; });
    return true;
  }

 private:
  /// Claim and run chunks until none is left.
  void take(void (*job)(void*, int), void* ctx, int n) {
    for (int c = next_.fetch_add(1); c < n; c = next_.fetch_add(1)) {
      job(ctx, c);
      done_.fetch_add(1, std::memory_order_release);
    }
  }

  void grow(int workers) {
    for (; started_ < workers; ++started_) std::thread([this] { work(); }).detach();
  }

  void work() {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lk(mu_);
    for (;;) {
      cv_.wait(lk, [&] { return gen_ != seen; });
      seen = gen_;
      if (!open_) continue;  // woken after the caller finished the loop alone
      ++active_;
      void (*job)(void*, int) = job_;
      void* ctx = ctx_;
      const int n = n_;
      lk.unlock();
      take(job, ctx, n);
      lk.lock();
      if (--active_ == 0) idle_.notify_all();
    }
  }

  std::mutex busy_;  // held by the thread whose loop the pool runs
  std::mutex mu_;    // guards what follows, up to the atomics
  std::condition_variable cv_, idle_;
  std::uint64_t gen_ = 0;
  bool open_ = false;
  int active_ = 0, n_ = 0, started_ = 0;
  void (*job_)(void*, int) = nullptr;
  void* ctx_ = nullptr;
  std::atomic<int> next_{0}, done_{0};
};

Pool& pool() {
  static Pool* p = new Pool();  // never destroyed (its threads outlive static destruction)
  return *p;
}

}  // namespace

void set_assembly_threads(int n) { g_threads.store(std::max(1, n)); }

int assembly_threads() { return g_threads.load(); }

bool run_chunks(int n_chunks, void (*job)(void* ctx, int chunk), void* ctx) {
  // a loop inside a chunk (a band solve in an element's job) runs on its thread alone: the
  // pool is this loop's, and its lock is not taken twice by one thread
  thread_local bool inside = false;
  if (n_chunks < 2 || g_threads.load() < 2 || inside) return false;
  inside = true;
  const bool ran = pool().run(n_chunks, job, ctx);
  inside = false;
  return ran;
}

}  // namespace rancf
