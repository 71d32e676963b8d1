#include "core/stage_clock.h"

#include <sys/resource.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <thread>

namespace isoquad {

namespace {

// Resident memory now, in bytes (second field of /proc/self/statm); -1 where there is
// no such file.
long long resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return -1;
  long long size = 0, resident = -1;
  if (std::fscanf(f, "%lld %lld", &size, &resident) != 2) resident = -1;
  std::fclose(f);
  return resident < 0 ? -1 : resident * static_cast<long long>(sysconf(_SC_PAGESIZE));
}

// Samples the resident memory every few milliseconds on a thread of its own and keeps the
// highest value since the last restart. The kernel's own high-water mark could be reset
// instead (/proc/self/clear_refs), but that also lowers the peak that getrusage and
// time(1) report for the whole process.
class ResidentSampler {
 public:
  static ResidentSampler& instance() {
    static ResidentSampler sampler;
    return sampler;
  }
  bool works() const { return works_; }
  void restart() { stage_max_ = resident_bytes(); }
  // The highest sample since the last restart, and the resident memory now.
  long long stage_max() {
    const long long now = resident_bytes();
    long long seen = stage_max_.load();
    while (now > seen && !stage_max_.compare_exchange_weak(seen, now)) {
    }
    return std::max(seen, now);
  }

 private:
  ResidentSampler() : works_(resident_bytes() > 0) {
    if (works_) thread_ = std::thread([this] { run(); });
  }
  ~ResidentSampler() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  void run() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(5), [this] { return stop_; }))
      stage_max();
  }

  const bool works_;
  std::atomic<long long> stage_max_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace

double process_peak_mb() {
  // The kernel's high-water mark of this process image's resident memory. getrusage's
  // ru_maxrss is not that: it keeps, across exec, the mark of the memory the process had
  // before, the parent's when started by vfork and exec as Python's subprocess does
  // (from a script holding 500 MB, France automatic reported 510 MB instead of 93).
  if (std::FILE* f = std::fopen("/proc/self/status", "r")) {
    char line[256];
    long long kb = -1;
    while (kb < 0 && std::fgets(line, sizeof line, f))
      if (std::sscanf(line, "VmHWM: %lld kB", &kb) != 1) kb = -1;
    std::fclose(f);
    if (kb >= 0) return kb / 1024.0;
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // kilobytes on Linux
}

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

void limit_heap_arenas(int arenas) {
#if defined(__GLIBC__)
  if (arenas >= 1) mallopt(M_ARENA_MAX, arenas);
#else
  (void)arenas;
#endif
}

bool stage_peaks_supported() {
  return ResidentSampler::instance().works();
}

StageClock::StageClock(std::vector<StageTime>& out) : out_(out) {
  start();
}

void StageClock::start() {
  if (stage_peaks_supported()) {
    ResidentSampler::instance().restart();
    process_peak_at_start_mb_ = process_peak_mb();
  }
  t0_ = std::chrono::steady_clock::now();
}

void StageClock::lap(const std::string& stage) {
  const auto now = std::chrono::steady_clock::now();
  double peak = process_peak_mb();
  // A stage that raised the process's high-water mark peaked there, however briefly;
  // the samples, every 5 ms when the sampler gets a core, could miss it.
  if (stage_peaks_supported() && peak <= process_peak_at_start_mb_)
    peak = ResidentSampler::instance().stage_max() / (1024.0 * 1024.0);
  out_.push_back({stage, std::chrono::duration<double>(now - t0_).count(), peak});
  start();
}

}  // namespace isoquad
