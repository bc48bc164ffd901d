// SPDX-License-Identifier: MIT
#include "rewind/net/polled_udp_socket.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

namespace rwd::net {
namespace {

using Endpoint = PolledUdpSocket::Endpoint;

Endpoint loopback(uint16_t port) {
  return Endpoint(asio::ip::make_address("127.0.0.1"), port);
}

// Drains until `want` datagrams arrived or a second passed: loopback
// delivery is quick but not synchronous with the send.
std::vector<std::vector<uint8_t>> receive(PolledUdpSocket& socket, size_t want,
                                          std::vector<Endpoint>* from = nullptr) {
  std::vector<std::vector<uint8_t>> got;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (got.size() < want && std::chrono::steady_clock::now() < deadline) {
    socket.drain([&](std::span<const uint8_t> bytes, const Endpoint& sender) {
      got.emplace_back(bytes.begin(), bytes.end());
      if (from) from->push_back(sender);
    });
    if (got.size() < want) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return got;
}

TEST(PolledUdpSocket, QueuedDatagramsLeaveInOrderAndDrainInBatches) {
  auto a = PolledUdpSocket::open("127.0.0.1", 0);
  auto b = PolledUdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_NE(a->local_port(), 0);
  // More than one batch each way.
  const size_t count = PolledUdpSocket::kBatch * 2 + 5;
  for (size_t i = 0; i < count; ++i) {
    const std::vector<uint8_t> bytes(1 + i, static_cast<uint8_t>(i));
    a->queue_send(bytes, loopback(b->local_port()));
  }
  EXPECT_EQ(a->flush_sends(), count);
  EXPECT_EQ(a->stats().datagrams_sent, count);
  EXPECT_EQ(a->flush_sends(), 0u);  // the queue was emptied
  std::vector<Endpoint> from;
  const auto got = receive(*b, count, &from);
  ASSERT_EQ(got.size(), count);
  for (size_t i = 0; i < count; ++i) {
    EXPECT_EQ(got[i].size(), 1 + i);
    EXPECT_EQ(got[i].front(), static_cast<uint8_t>(i));
    EXPECT_EQ(from[i].port(), a->local_port());
  }
  EXPECT_EQ(b->stats().datagrams_received, count);
  // Nothing waiting: a drain returns at once with nothing.
  EXPECT_EQ(b->drain([](std::span<const uint8_t>, const Endpoint&) { FAIL(); }), 0u);
}

TEST(PolledUdpSocket, DrainStopsAtItsLimitAndKeepsTheRest) {
  auto a = PolledUdpSocket::open("127.0.0.1", 0);
  auto b = PolledUdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(a.ok() && b.ok());
  const uint8_t byte = 7;
  for (int i = 0; i < 10; ++i) a->queue_send({&byte, 1}, loopback(b->local_port()));
  a->flush_sends();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  size_t seen = 0;
  EXPECT_EQ(b->drain([&](std::span<const uint8_t>, const Endpoint&) { ++seen; }, 4), 4u);
  EXPECT_EQ(seen, 4u);
  EXPECT_EQ(receive(*b, 6).size(), 6u);
}

TEST(PolledUdpSocket, OversizedDatagramsArriveCutAndRefusedSendsAreCounted) {
  auto a = PolledUdpSocket::open("127.0.0.1", 0);
  auto b = PolledUdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(a.ok() && b.ok());
  a->queue_send(std::vector<uint8_t>(PolledUdpSocket::kMaxDatagram + 500, 1),
                loopback(b->local_port()));
  // An IPv6 destination from an IPv4 socket is refused by the OS; the
  // datagram after it still leaves.
  a->queue_send(std::vector<uint8_t>(3, 2), Endpoint(asio::ip::make_address("::1"), 9));
  a->queue_send(std::vector<uint8_t>(3, 3), loopback(b->local_port()));
  EXPECT_EQ(a->flush_sends(), 2u);
  EXPECT_EQ(a->stats().send_errors, 1u);
  const auto got = receive(*b, 2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].size(), PolledUdpSocket::kMaxDatagram);
  EXPECT_EQ(got[1], std::vector<uint8_t>(3, 3));
}

TEST(PolledUdpSocket, BadAddressesAndTakenPortsAreClearErrors) {
  auto bad = PolledUdpSocket::open("not-an-address", 0);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), ErrorCode::kInvalidArgument);
  auto a = PolledUdpSocket::open("127.0.0.1", 0);
  ASSERT_TRUE(a.ok());
  auto taken = PolledUdpSocket::open("127.0.0.1", a->local_port());
  ASSERT_FALSE(taken.ok());
  EXPECT_EQ(taken.status().code(), ErrorCode::kIo);
  EXPECT_NE(taken.status().message().find(std::to_string(a->local_port())), std::string::npos);
  // Closed: sends are dropped quietly, drains find nothing.
  a->close();
  EXPECT_FALSE(a->is_open());
  const uint8_t byte = 1;
  a->queue_send({&byte, 1}, loopback(9));
  EXPECT_EQ(a->flush_sends(), 0u);
  EXPECT_EQ(a->drain([](std::span<const uint8_t>, const Endpoint&) {}), 0u);
}

}  // namespace
}  // namespace rwd::net
