#pragma once
// Test support: the message of an InvalidInput, checked to be one line.

#include <gtest/gtest.h>

#include <string>

#include "geolens/core/errors.h"

namespace geolens::test {

/// The message of the InvalidInput `call` throws ("" if it throws none), checked to be one line.
template <typename Call>
std::string refusal(Call call) {
  try {
    call();
  } catch (const InvalidInput& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  return "";
}

}  // namespace geolens::test
