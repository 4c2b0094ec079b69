// Errors and exit codes shared by every walkrad command (README.md, "Exit codes").
#pragma once

#include <stdexcept>
#include <string>

namespace walkrad {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,        // a bug: please report it
  kExitBadArguments = 2,    // the command line is wrong
  kExitBadInput = 3,        // an input file is missing, unreadable or invalid
  kExitMissingFeature = 4,  // valid input that uses something walkrad does not support
  kExitOutputFailure = 5,   // the output could not be written
  kExitLimitReached = 6,    // a size, count or time limit was reached
  kExitDiffers = 7,         // `walkrad diff`: the bakes differ beyond the tolerance
};

// A refusal of an input file: names the file, the place in it (JSON pointer, line, accessor) and
// the rule broken. what() reads "FILE: PLACE: MESSAGE".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string place, std::string message, ExitCode code = kExitBadInput)
      : std::runtime_error(compose(file, place, message)),
        file_(std::move(file)), place_(std::move(place)), message_(std::move(message)), code_(code) {}

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }
  const std::string& message() const { return message_; }
  ExitCode code() const { return code_; }

 private:
  static std::string compose(const std::string& f, const std::string& p, const std::string& m) {
    return p.empty() ? f + ": " + m : f + ": " + p + ": " + m;
  }
  std::string file_, place_, message_;
  ExitCode code_;
};

// The output could not be written (disk full, permissions): exit code kExitOutputFailure.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace walkrad
