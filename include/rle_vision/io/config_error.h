// The error every configuration reader throws: "file:line: reason".
#pragma once

#include <stdexcept>

namespace rle_vision {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rle_vision
