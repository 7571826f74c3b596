// Shared by the reference shims only (not part of their C interface).
#ifndef DELMESH_C_TESTS_REF_INTERNAL_HPP
#define DELMESH_C_TESTS_REF_INTERNAL_HPP

#include <chrono>
#include <cstdint>
#include <limits>

namespace ref {

// Records the message returned by ref_last_error(); returns -1 for `return fail(...)`.
int fail(const char *message);

// Wall-clock stopwatch (steady clock, like the benchmark's CLOCK_MONOTONIC).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Indices are returned as uint32_t; larger inputs are refused up front.
inline bool fits_u32(std::size_t n) { return n <= std::numeric_limits<std::uint32_t>::max(); }

}  // namespace ref

#endif
