#pragma once
// SKIP_WITHOUT_EGL(statement): tests that need an EGL display run `statement` (which makes the
// first GL context) and are skipped with the reason where none can be made, unless
// TILEKIT_REQUIRE_EGL=1 (scripts/test.sh sets it after scripts/setup.sh has installed Mesa's EGL,
// so CI cannot pass by skipping them): then a missing context fails the test.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "render/gl_renderer.hpp"

#define SKIP_WITHOUT_EGL(statement)                                                                   \
  try {                                                                                               \
    statement;                                                                                        \
  } catch (const GlUnavailable& e) {                                                                  \
    const char* required = std::getenv("TILEKIT_REQUIRE_EGL");                                        \
    if (required && std::string(required) == "1") FAIL() << "TILEKIT_REQUIRE_EGL=1 but " << e.what(); \
    GTEST_SKIP() << "no EGL context: " << e.what();                                                   \
  }
