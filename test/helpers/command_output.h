// Runs one of the package's programs as a user would, for the tests of its command line.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace deformable_sim::test {

struct CommandOutput {
  int exit_code = -1;
  std::string output;  ///< what it wrote to stdout (a command ending in 2>&1: stderr too)
};

/// Runs `command` through the shell and waits for it.
inline CommandOutput runCommand(const std::string& command) {
  CommandOutput result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  result.exit_code = WEXITSTATUS(pclose(pipe));
  return result;
}

}  // namespace deformable_sim::test
