// The progress bar of work that is usually quick: nothing until its delay has passed.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "deformable_sim/core/base/late_progress_bar.h"

namespace {

std::string textOf(std::FILE* file) {
  std::rewind(file);
  std::string text;
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file)) text += static_cast<char>(c);
  return text;
}

}  // namespace

TEST(LateProgressBar, QuickWorkWritesNothing) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  deformable_sim::core::LateProgressBar bar(log, "cells", 1e9);
  for (long done = 0; done <= 100; ++done) bar.update(done, 100);
  bar.finish();
  EXPECT_FALSE(bar.shown());
  EXPECT_EQ(textOf(log), "");
  std::fclose(log);
}

TEST(LateProgressBar, SlowWorkShowsTheBarAndItsTotal) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  deformable_sim::core::LateProgressBar bar(log, "cells", 0.0);
  for (long done = 0; done <= 100; ++done) bar.update(done, 100);
  bar.finish();
  EXPECT_TRUE(bar.shown());
  const std::string text = textOf(log);
  EXPECT_NE(text.find("100/100"), std::string::npos) << text;
  EXPECT_NE(text.find("100 cells in"), std::string::npos) << text;
  std::fclose(log);
}
