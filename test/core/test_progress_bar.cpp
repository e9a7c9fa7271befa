// The progress bar in a log (not a terminal): one line a tenth, however often it is updated, so
// that a re-simulation can update it every step.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "deformable_sim/core/base/progress_bar.h"

namespace {

std::vector<std::string> linesOf(std::FILE* file) {
  std::rewind(file);
  std::vector<std::string> lines;
  std::string line;
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file)) {
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else {
      line += static_cast<char>(c);
    }
  }
  return lines;
}

}  // namespace

TEST(ProgressBar, InALogItWritesOneLineATenthAndTheTotalAtTheEnd) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    deformable_sim::core::ProgressBar bar(1000, log, "steps");
    for (long done = 0; done <= 1000; ++done) bar.update(done);
    bar.finish();
  }
  const std::vector<std::string> lines = linesOf(log);
  std::fclose(log);
  ASSERT_EQ(lines.size(), 12u);  // 0 %, 10 %, ..., 100 %, and the total
  EXPECT_NE(lines[0].find("0/1000"), std::string::npos) << lines[0];
  EXPECT_NE(lines[10].find("100% 1000/1000"), std::string::npos) << lines[10];
  EXPECT_EQ(lines[11].rfind("1000 steps in ", 0), 0u) << lines[11];
}

TEST(ProgressBar, MoreDoneThanPlannedStaysAtTheFullBar) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  {
    deformable_sim::core::ProgressBar bar(10, log, "settings");
    bar.update(10, "last");
    bar.update(25, "beyond");
  }
  const std::vector<std::string> lines = linesOf(log);
  std::fclose(log);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("100%"), std::string::npos) << lines[0];
}
