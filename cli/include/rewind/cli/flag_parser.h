// SPDX-License-Identifier: MIT
#pragma once
// Strict command-line flags for Rewind's programs: every flag is declared
// with its type, range and help line; unknown flags, missing values and
// malformed or out-of-range numbers are errors that name the flag.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rewind/core/status.h"

namespace rwd::cli {

class FlagParser {
 public:
  /// `usage` is the first help line, e.g. "rewind-server [flags]".
  FlagParser(std::string program, std::string usage, std::string description);

  void add_string(const std::string& name, std::string* target, const std::string& help);
  void add_bool(const std::string& name, bool* target, const std::string& help);
  void add_int(const std::string& name, int64_t* target, int64_t min, int64_t max,
               const std::string& help);
  void add_double(const std::string& name, double* target, double min, double max,
                  const std::string& help);
  /// A flag that may be given many times: each occurrence appends its value
  /// to `target` (e.g. "--budget a=1 --budget b=2").
  void add_string_list(const std::string& name, std::vector<std::string>* target,
                       const std::string& help);

  /// Parses argv[first..]. Accepts "--name value" and "--name=value"; bool
  /// flags take no value ("--name") or an explicit "--name=true|false".
  /// Positional arguments are collected when `positionals` is non-null.
  /// Returns kInvalidArgument with a message naming the flag on error.
  Status parse(int argc, const char* const* argv, int first = 1,
               std::vector<std::string>* positionals = nullptr);
  /// True when --help or -h was given (parse() then returns Ok early).
  bool help_requested() const { return help_; }
  /// The full help text: usage, description, one line per flag with default.
  std::string help_text() const;

 private:
  enum class Kind : uint8_t { kString, kBool, kInt, kDouble, kStringList };
  struct Flag {
    std::string name;
    Kind kind;
    void* target;
    int64_t int_min = 0, int_max = 0;
    double double_min = 0, double_max = 0;
    std::string help;
    std::string default_text;
  };
  Status assign(const Flag& flag, const std::string& value);

  std::string program_;
  std::string usage_;
  std::string description_;
  std::vector<Flag> flags_;
  bool help_ = false;
};

/// Exit code for usage errors (BSD sysexits EX_USAGE).
inline constexpr int kExitUsage = 64;

}  // namespace rwd::cli
