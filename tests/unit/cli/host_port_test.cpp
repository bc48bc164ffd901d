// SPDX-License-Identifier: MIT
#include "rewind/cli/host_port.h"

#include <gtest/gtest.h>

namespace rwd::cli {
namespace {

TEST(SplitHostPort, SplitsNamesAndLiterals) {
  std::string host;
  uint16_t port = 1;
  ASSERT_TRUE(split_host_port("127.0.0.1:9100", &host, &port));
  EXPECT_EQ(host, "127.0.0.1");
  EXPECT_EQ(port, 9100);
  ASSERT_TRUE(split_host_port("server:7777", &host, &port));
  EXPECT_EQ(host, "server");
  ASSERT_TRUE(split_host_port("[::1]:0", &host, &port));
  EXPECT_EQ(host, "::1");
  EXPECT_EQ(port, 0);
  ASSERT_TRUE(split_host_port("0.0.0.0:65535", &host, &port));
  EXPECT_EQ(port, 65535);
}

TEST(SplitHostPort, RefusesWhatIsNotHostColonPort) {
  std::string host = "untouched";
  uint16_t port = 1;
  for (const char* bad :
       {"nowhere", ":9100", "host:", "host:65536", "host:12a", "host:-1", "host:123456", ""}) {
    EXPECT_FALSE(split_host_port(bad, &host, &port)) << bad;
  }
  EXPECT_EQ(host, "untouched");
  EXPECT_EQ(port, 1);
}

}  // namespace
}  // namespace rwd::cli
