#pragma once
// The message of the dnurbs::Error an action throws, for tests that check what errors say.

#include <string>

#include <gtest/gtest.h>

#include "dnurbs/core/error.h"

namespace dnurbs::testing {

/// Runs `action` and returns the message of the dnurbs::Error it throws; fails the test if it
/// throws nothing.
template <typename Action>
std::string error_message(Action action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no dnurbs::Error thrown";
  return {};
}

}  // namespace dnurbs::testing
