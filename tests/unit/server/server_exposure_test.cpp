// SPDX-License-Identifier: MIT
// Tokenless only where it is safe: a server without a key refuses to start
// on an address other hosts reach, saying how to run secure, unless the
// operator allows it; on loopback, or with a key, it starts.
#include <gtest/gtest.h>

#include "rewind/server/server.h"

namespace rwd::server {
namespace {

ServerConfig tokenless_on(const std::string& address) {
  ServerConfig config;
  config.bind_address = address;
  config.port = 0;
  return config;
}

TEST(ServerExposure, LoopbackIsTheLoopbackNetworkOnly) {
  for (const char* loopback : {"127.0.0.1", "127.0.0.2", "127.255.255.254", "::1",
                               "::ffff:127.0.0.1", "::ffff:127.9.8.7"}) {
    EXPECT_TRUE(is_loopback_address(loopback)) << loopback;
  }
  for (const char* reachable :
       {"0.0.0.0", "::", "10.0.0.1", "192.168.1.20", "128.0.0.1", "::ffff:10.0.0.1",
        "::ffff:0.0.0.0", "fe80::1", "2001:db8::1", "localhost", ""}) {
    EXPECT_FALSE(is_loopback_address(reachable)) << reachable;
  }
}

TEST(ServerExposure, TokenlessOnAReachableAddressIsRefusedWithTheWayToRunSecure) {
  for (const char* address : {"0.0.0.0", "::"}) {
    auto server = Server::create(tokenless_on(address));
    ASSERT_FALSE(server.ok()) << address;
    EXPECT_EQ(server.status().code(), ErrorCode::kInvalidArgument);
    const std::string& message = server.status().message();
    EXPECT_NE(message.find("rewind-token keygen"), std::string::npos) << message;
    EXPECT_NE(message.find("--key-file"), std::string::npos) << message;
    EXPECT_NE(message.find("--insecure-tokenless-on-public-address"), std::string::npos);
  }
}

TEST(ServerExposure, LoopbackAKeyOrTheOperatorsWordLetItStart) {
  EXPECT_TRUE(Server::create(tokenless_on("127.0.0.1")).ok());
  EXPECT_TRUE(check_tokenless_exposure(tokenless_on("::1")).ok());
  ServerConfig secure = tokenless_on("0.0.0.0");
  secure.server_key = net::generate_key();
  EXPECT_TRUE(Server::create(secure).ok());
  ServerConfig allowed = tokenless_on("0.0.0.0");
  allowed.insecure_tokenless_public = true;
  EXPECT_TRUE(Server::create(allowed).ok());
  EXPECT_TRUE(check_tokenless_exposure(allowed).ok());
  EXPECT_FALSE(check_tokenless_exposure(tokenless_on("0.0.0.0")).ok());
}

}  // namespace
}  // namespace rwd::server
