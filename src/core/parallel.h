// Two independent pieces of work at once: the second on a thread of its own. Each must
// touch only its own state (a GEOS context, say); the results are the same as when they
// run one after the other.
#pragma once

#include <exception>
#include <thread>
#include <utility>

namespace isoquad {

// Runs a() here and b() on another thread, and returns when both are done. An exception
// from either is rethrown here (a's first), after both have finished.
template <class A, class B>
void run_in_parallel(A&& a, B&& b) {
  std::exception_ptr b_error;
  std::thread other([&] {
    try {
      b();
    } catch (...) {
      b_error = std::current_exception();
    }
  });
  std::exception_ptr a_error;
  try {
    a();
  } catch (...) {
    a_error = std::current_exception();
  }
  other.join();
  if (a_error) std::rethrow_exception(a_error);
  if (b_error) std::rethrow_exception(b_error);
}

}  // namespace isoquad
