// The message a refusal carries, for the tests that check what a reader tells its user.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace deformable_sim::test {

/// The message of the `Error` that `action` throws; a test failure saying `unthrown` (and "")
/// when it throws none.
template <typename Error, typename Action>
std::string thrownMessage(Action&& action, const std::string& unthrown) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << unthrown;
  return "";
}

}  // namespace deformable_sim::test
