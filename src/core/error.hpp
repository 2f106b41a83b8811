#pragma once
// One exception type for every user-facing failure; the CLI maps its kind to an exit code.
#include <stdexcept>
#include <string>

namespace fluidbed {

enum class ErrorKind {
  BadInput = 2,          ///< case file, command line, restart file
  SimulationFailed = 3,  ///< NaN, instability, solver failure
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  ErrorKind kind() const { return kind_; }
  int exit_code() const { return static_cast<int>(kind_); }

 private:
  ErrorKind kind_;
};

[[noreturn]] inline void throw_input_error(const std::string& message) {
  throw Error(ErrorKind::BadInput, message);
}
[[noreturn]] inline void throw_simulation_error(const std::string& message) {
  throw Error(ErrorKind::SimulationFailed, message);
}

}  // namespace fluidbed
