// Shared by the io tests: an rk::Error expected from a call, with its exit code and a piece of its message.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "io/error.h"

namespace rk::io {

// Runs `f`, expects an rk::Error with `code` whose message contains `needle`.
template <typename F>
inline void ExpectError(F f, ExitCode code, const std::string& needle) {
  try {
    f();
    FAIL() << "no error thrown; expected one containing '" << needle << "'";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace rk::io
