#pragma once
// The bad-input message a case gives: every error of the loader is exit 2; an accepted case is a test failure.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "config/case_loader.hpp"

namespace fluidbed {

inline std::string error_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  try {
    load_case_text(text, "t.toml", sets);
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << text;
  return "";
}

}  // namespace fluidbed
