// Invariants checked where they hold, in debug and sanitizer builds: NDEBUG unset, or
// WALKRAD_CHECK_INVARIANTS defined (cmake/WalkradSanitizers.cmake defines it). A broken invariant
// ends the process with what broke and where (a bug, not a fault of the input: input is checked
// with InputError); a release build evaluates none of them. The checks that walk a whole structure
// are functions that name the first fault ("" when there is none), so that tests call them in any
// build and the solver calls them through WALKRAD_CHECK_FAULT.
#pragma once

#include <string>

#if !defined(NDEBUG) || defined(WALKRAD_CHECK_INVARIANTS)
#define WALKRAD_CHECKS 1
#else
#define WALKRAD_CHECKS 0
#endif

namespace walkrad {

// Prints "walkrad: invariant broken at FILE:LINE: WHAT" and aborts.
[[noreturn]] void invariant_broken(const char* file, int line, const std::string& what);

}  // namespace walkrad

#define WALKRAD_INVARIANT(condition, what)                                                   \
  do {                                                                                       \
    if (WALKRAD_CHECKS && !(condition)) ::walkrad::invariant_broken(__FILE__, __LINE__, what); \
  } while (0)

// fault: an expression naming the first fault of a structure, "" when it holds; evaluated only in
// checked builds.
#define WALKRAD_CHECK_FAULT(fault)                                                        \
  do {                                                                                    \
    if (WALKRAD_CHECKS) {                                                                 \
      const std::string walkrad_fault_ = (fault);                                         \
      if (!walkrad_fault_.empty()) ::walkrad::invariant_broken(__FILE__, __LINE__, walkrad_fault_); \
    }                                                                                     \
  } while (0)
