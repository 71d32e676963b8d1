// Seconds and peak resident memory of each stage of a job.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace isoquad {

struct StageTime {
  std::string stage;
  double seconds = 0.0;
  // The stage's own peak resident memory, in MB: the process's high-water mark when the
  // stage raised it, else the highest of samples taken every 5 ms from the stage's start
  // (/proc/self/statm). Where that file is missing, the process peak so far.
  double peak_mb = 0.0;
};

// The process's peak resident memory since it started, in MB (VmHWM; where
// /proc/self/status is missing, getrusage's ru_maxrss).
double process_peak_mb();

// True when stages get their own peaks (resident memory can be sampled here).
bool stage_peaks_supported();

// Hands the heap's free pages back to the system (glibc's malloc_trim; elsewhere
// nothing), so that memory a stage freed in many small blocks is not counted resident
// beside the next stage's large arrays.
void release_free_memory();

// Lets the heap keep at most `arenas` pools (glibc's M_ARENA_MAX; elsewhere nothing). By
// default glibc gives threads that meet at malloc pools of their own, up to eight per
// core, and memory freed in one pool serves only the threads using it: the stages'
// helper threads then hold freed blocks that the next stage cannot reuse. One pool per
// region meshed at once (--jobs) keeps the same speed (France at 1.5 km: the tiling's
// peak 586 -> 558 MB; 56 countries at 1:50m with --jobs 2: 294 to 319 -> 268 to 287 MB,
// 33 to 34 s either way; one pool for the two regions: 36.2 s). Call before any thread
// starts: glibc fixes its limit when a thread first needs a pool.
void limit_heap_arenas(int arenas);

// Starts a stage at construction and at every lap; lap() appends the stage just ended.
class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& out);
  void lap(const std::string& stage);

 private:
  void start();
  std::vector<StageTime>& out_;
  std::chrono::steady_clock::time_point t0_;
  double process_peak_at_start_mb_ = 0.0;
};

}  // namespace isoquad
