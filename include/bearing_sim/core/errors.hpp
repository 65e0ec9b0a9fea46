#pragma once
#include <stdexcept>
#include <string>

namespace bearing_sim {

// A bearing file that is missing, malformed, or has a key that is unknown, of the
// wrong type or out of range. what() names the file and the key.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A load the bearing cannot carry (no equilibrium exists, or it lies beyond the
// geometry the model is valid for).
class LoadNotCarriedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A non-finite or runaway dynamic state.
class DivergenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Any other bad argument to the library (NaN load, negative duration, ...).
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace bearing_sim
