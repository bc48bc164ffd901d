// SPDX-License-Identifier: MIT
#include "rewind/cli/flag_parser.h"

#include <gtest/gtest.h>

#include <vector>

namespace rwd::cli {
namespace {

struct Parsed {
  std::string name = "x";
  int64_t count = 3;
  double ratio = 0.5;
  bool verbose = false;
  Status status;
  bool help = false;
  std::vector<std::string> positionals;
};

Parsed parse(std::vector<const char*> args) {
  Parsed p;
  FlagParser flags("prog", "prog [flags]", "test program");
  flags.add_string("name", &p.name, "a name");
  flags.add_int("count", &p.count, 1, 10, "a count");
  flags.add_double("ratio", &p.ratio, 0, 1, "a ratio");
  flags.add_bool("verbose", &p.verbose, "talk more");
  args.insert(args.begin(), "prog");
  p.status = flags.parse(static_cast<int>(args.size()), args.data(), 1, &p.positionals);
  p.help = flags.help_requested();
  return p;
}

TEST(FlagParser, AcceptsBothSpellingsAndBools) {
  Parsed p = parse({"--name", "alpha", "--count=7", "--ratio", "0.25", "--verbose", "file"});
  ASSERT_TRUE(p.status.ok()) << p.status.message();
  EXPECT_EQ(p.name, "alpha");
  EXPECT_EQ(p.count, 7);
  EXPECT_DOUBLE_EQ(p.ratio, 0.25);
  EXPECT_TRUE(p.verbose);
  EXPECT_EQ(p.positionals, std::vector<std::string>{"file"});
  EXPECT_FALSE(parse({"--verbose=false"}).verbose);
}

TEST(FlagParser, ErrorsNameTheFlagAndLeaveDefaults) {
  struct Case {
    std::vector<const char*> args;
    const char* expected;
  };
  const Case cases[] = {
      {{"--nope"}, "unknown flag --nope"},
      {{"--count"}, "--count: missing value"},
      {{"--count", "12"}, "--count: 12 is outside [1, 10]"},
      {{"--count", "3x"}, "--count: expected an integer, got '3x'"},
      {{"--count="}, "--count: expected an integer, got ''"},
      {{"--count", "99999999999999999999"}, "--count: expected an integer"},
      {{"--ratio", "nan"}, "--ratio: expected a finite number, got 'nan'"},
      {{"--ratio", "1.5"}, "--ratio: 1.5 is outside [0, 1]"},
      {{"--verbose=maybe"}, "--verbose: expected true or false"},
      {{"-x"}, "unexpected argument '-x'"},
  };
  for (const Case& c : cases) {
    Parsed p = parse(c.args);
    ASSERT_FALSE(p.status.ok()) << c.expected;
    EXPECT_NE(p.status.message().find(c.expected), std::string::npos) << p.status.message();
    EXPECT_EQ(p.count, 3);
  }
}

TEST(FlagParser, RepeatedListFlagsAppendInOrder) {
  std::vector<std::string> budgets;
  FlagParser flags("prog", "prog [flags]", "test program");
  flags.add_string_list("budget", &budgets, "a limit");
  const char* args[] = {"prog", "--budget", "a=1", "--budget=b=2", "--budget", "a=3"};
  ASSERT_TRUE(flags.parse(6, args).ok());
  EXPECT_EQ(budgets, (std::vector<std::string>{"a=1", "b=2", "a=3"}));
  const char* missing[] = {"prog", "--budget"};
  EXPECT_EQ(flags.parse(2, missing).message(), "--budget: missing value");
  EXPECT_NE(flags.help_text().find("--budget STR..."), std::string::npos);
  EXPECT_NE(flags.help_text().find("(repeatable)"), std::string::npos);
}

TEST(FlagParser, HelpStopsParsingAndListsEveryFlag) {
  Parsed p = parse({"--help", "--nope"});
  EXPECT_TRUE(p.status.ok());
  EXPECT_TRUE(p.help);
  FlagParser flags("prog", "prog [flags]", "does things");
  int64_t n = 4;
  flags.add_int("count", &n, 1, 10, "a count");
  const std::string help = flags.help_text();
  EXPECT_NE(help.find("usage: prog [flags]"), std::string::npos);
  EXPECT_NE(help.find("--count N"), std::string::npos);
  EXPECT_NE(help.find("(default 4)"), std::string::npos);
  EXPECT_NE(help.find("--help"), std::string::npos);
}

}  // namespace
}  // namespace rwd::cli
