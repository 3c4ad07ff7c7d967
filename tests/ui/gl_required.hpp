// Tests that need OpenGL: without a context they are skipped, except under the test command
// (scripts/test.sh sets FAULTLINE_REQUIRE_GL=1, with Xvfb and llvmpipe), where a skip would hide
// that nothing was drawn: there they fail.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>

#define FAULTLINE_NEED_GL(reason)                                                                  \
    do {                                                                                           \
        if (const char* required = std::getenv("FAULTLINE_REQUIRE_GL");                            \
            required && *required == '1')                                                          \
            FAIL() << reason << " (FAULTLINE_REQUIRE_GL=1: OpenGL is required here)";              \
        else                                                                                       \
            GTEST_SKIP() << reason;                                                                \
    } while (0)
