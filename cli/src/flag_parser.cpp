// SPDX-License-Identifier: MIT
#include "rewind/cli/flag_parser.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace rwd::cli {

FlagParser::FlagParser(std::string program, std::string usage, std::string description)
    : program_(std::move(program)),
      usage_(std::move(usage)),
      description_(std::move(description)) {}

void FlagParser::add_string(const std::string& name, std::string* target, const std::string& help) {
  flags_.push_back({name, Kind::kString, target, 0, 0, 0, 0, help, "\"" + *target + "\""});
}

void FlagParser::add_bool(const std::string& name, bool* target, const std::string& help) {
  flags_.push_back({name, Kind::kBool, target, 0, 0, 0, 0, help, *target ? "true" : "false"});
}

void FlagParser::add_int(const std::string& name, int64_t* target, int64_t min, int64_t max,
                         const std::string& help) {
  flags_.push_back({name, Kind::kInt, target, min, max, 0, 0, help, std::to_string(*target)});
}

void FlagParser::add_double(const std::string& name, double* target, double min, double max,
                            const std::string& help) {
  std::ostringstream text;
  text << *target;
  flags_.push_back({name, Kind::kDouble, target, 0, 0, min, max, help, text.str()});
}

void FlagParser::add_string_list(const std::string& name, std::vector<std::string>* target,
                                 const std::string& help) {
  flags_.push_back({name, Kind::kStringList, target, 0, 0, 0, 0, help, ""});
}

Status FlagParser::assign(const Flag& flag, const std::string& value) {
  auto bad = [&](const std::string& why) {
    return Status::Error(ErrorCode::kInvalidArgument, "--" + flag.name + ": " + why);
  };
  switch (flag.kind) {
    case Kind::kString:
      *static_cast<std::string*>(flag.target) = value;
      return Status::Ok();
    case Kind::kStringList:
      static_cast<std::vector<std::string>*>(flag.target)->push_back(value);
      return Status::Ok();
    case Kind::kBool:
      if (value == "true" || value == "1") {
        *static_cast<bool*>(flag.target) = true;
      } else if (value == "false" || value == "0") {
        *static_cast<bool*>(flag.target) = false;
      } else {
        return bad("expected true or false, got '" + value + "'");
      }
      return Status::Ok();
    case Kind::kInt: {
      if (value.empty()) return bad("expected an integer, got ''");
      errno = 0;
      char* end = nullptr;
      const long long v = std::strtoll(value.c_str(), &end, 10);
      if (errno != 0 || end == value.c_str() || *end != '\0') {
        return bad("expected an integer, got '" + value + "'");
      }
      if (v < flag.int_min || v > flag.int_max) {
        return bad(value + " is outside [" + std::to_string(flag.int_min) + ", " +
                   std::to_string(flag.int_max) + "]");
      }
      *static_cast<int64_t*>(flag.target) = v;
      return Status::Ok();
    }
    case Kind::kDouble: {
      if (value.empty()) return bad("expected a number, got ''");
      errno = 0;
      char* end = nullptr;
      const double v = std::strtod(value.c_str(), &end);
      if (errno != 0 || end == value.c_str() || *end != '\0' || !std::isfinite(v)) {
        return bad("expected a finite number, got '" + value + "'");
      }
      if (v < flag.double_min || v > flag.double_max) {
        std::ostringstream range;
        range << value << " is outside [" << flag.double_min << ", " << flag.double_max << "]";
        return bad(range.str());
      }
      *static_cast<double*>(flag.target) = v;
      return Status::Ok();
    }
  }
  return bad("unsupported flag kind");
}

Status FlagParser::parse(int argc, const char* const* argv, int first,
                         std::vector<std::string>* positionals) {
  for (int i = first; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help_ = true;
      return Status::Ok();
    }
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
      if (positionals != nullptr && (arg.empty() || arg[0] != '-')) {
        positionals->push_back(arg);
        continue;
      }
      return Status::Error(ErrorCode::kInvalidArgument,
                           "unexpected argument '" + arg + "' (see " + program_ + " --help)");
    }
    std::string name = arg.substr(2);
    std::string value;
    bool has_value = false;
    if (size_t eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    const Flag* flag = nullptr;
    for (const Flag& f : flags_) {
      if (f.name == name) flag = &f;
    }
    if (flag == nullptr) {
      return Status::Error(ErrorCode::kInvalidArgument,
                           "unknown flag --" + name + " (see " + program_ + " --help)");
    }
    if (!has_value) {
      if (flag->kind == Kind::kBool) {
        value = "true";
      } else if (i + 1 < argc) {
        value = argv[++i];
      } else {
        return Status::Error(ErrorCode::kInvalidArgument, "--" + name + ": missing value");
      }
    }
    Status status = assign(*flag, value);
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

std::string FlagParser::help_text() const {
  std::ostringstream out;
  out << "usage: " << usage_ << "\n\n" << description_ << "\n\nflags:\n";
  for (const Flag& f : flags_) {
    std::string left = "  --" + f.name;
    switch (f.kind) {
      case Kind::kString:
        left += " STR";
        break;
      case Kind::kStringList:
        left += " STR...";
        break;
      case Kind::kInt:
        left += " N";
        break;
      case Kind::kDouble:
        left += " X";
        break;
      case Kind::kBool:
        break;
    }
    if (left.size() < 26) left.resize(26, ' ');
    if (f.kind == Kind::kStringList) {
      out << left << " " << f.help << " (repeatable)\n";
    } else {
      out << left << " " << f.help << " (default " << f.default_text << ")\n";
    }
  }
  out << "  --help                   print this help and exit\n";
  return out.str();
}

}  // namespace rwd::cli
