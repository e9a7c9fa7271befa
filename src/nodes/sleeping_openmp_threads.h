// OpenMP's threads (the element and node loops) spin between parallel loops by default, which is
// fastest on an idle machine and slowest beside another job: a spinning thread holds the core the
// other job and its own sleeping partner need. The shipped pile offline took 44 ms a step instead
// of 19 with one core busy beside it, and 26 with threads that sleep (doc/performance.md). The
// launch files set OMP_WAIT_POLICY=PASSIVE for the node; the programs see to it themselves.
// libgomp reads the variable once, as the program loads, so a program that finds it unset sets it
// and starts itself again; a value the user set is kept.
#pragma once

#include <unistd.h>

#include <cstdlib>

namespace deformable_sim {

inline void letOpenMpThreadsSleep(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
  execv("/proc/self/exe", argv);  // returns only when it failed: go on with spinning threads
}

}  // namespace deformable_sim
