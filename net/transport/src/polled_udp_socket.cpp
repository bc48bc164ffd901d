// SPDX-License-Identifier: MIT
#include "rewind/net/polled_udp_socket.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

namespace rwd::net {
namespace {

std::error_code last_os_error() {
  return {errno, std::system_category()};
}

}  // namespace

Result<PolledUdpSocket> PolledUdpSocket::open(std::string_view address, uint16_t port) {
  std::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(std::string(address), ec);
  if (ec) {
    return Status::Error(ErrorCode::kInvalidArgument,
                         "udp: bad address '" + std::string(address) + "': " + ec.message());
  }
  Endpoint endpoint(ip, port);
  const auto refused = [&](const char* what) {
    return Status::Error(ErrorCode::kIo, std::string("udp: cannot ") + what + " " +
                                             std::string(address) + ":" + std::to_string(port) +
                                             ": " + last_os_error().message());
  };
  const int fd = ::socket(ip.is_v6() ? AF_INET6 : AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return refused("open a socket for");
  if (::bind(fd, endpoint.data(), static_cast<socklen_t>(endpoint.size())) != 0) {
    Status status = refused("bind");
    ::close(fd);
    return status;
  }
  // Never block: a full send buffer drops the datagram, an empty socket
  // ends a drain.
  const int flags = ::fcntl(fd, F_GETFL, 0);
  Endpoint local;
  socklen_t length = static_cast<socklen_t>(local.capacity());
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags | O_NONBLOCK) != 0 ||
      ::getsockname(fd, local.data(), &length) != 0) {
    Status status = refused("set up");
    ::close(fd);
    return status;
  }
  local.resize(length);
  return PolledUdpSocket(fd, local);
}

PolledUdpSocket::PolledUdpSocket(int fd, Endpoint local) : fd_(fd), local_(local) {}

PolledUdpSocket::PolledUdpSocket(PolledUdpSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      local_(other.local_),
      stats_(other.stats_),
      receive_buffer_(std::move(other.receive_buffer_)),
      queued_bytes_(std::move(other.queued_bytes_)),
      queued_(std::move(other.queued_)) {}

PolledUdpSocket& PolledUdpSocket::operator=(PolledUdpSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    local_ = other.local_;
    stats_ = other.stats_;
    receive_buffer_ = std::move(other.receive_buffer_);
    queued_bytes_ = std::move(other.queued_bytes_);
    queued_ = std::move(other.queued_);
  }
  return *this;
}

PolledUdpSocket::~PolledUdpSocket() {
  close();
}

void PolledUdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  queued_.clear();
  queued_bytes_.clear();
}

size_t PolledUdpSocket::drain(const ReceiveHandler& handler, size_t max) {
  size_t delivered = 0;
  receive_buffer_.resize(kBatch * kMaxDatagram);
#if defined(__linux__)
  mmsghdr messages[kBatch];
  iovec vectors[kBatch];
  Endpoint senders[kBatch];
  while (delivered < max && fd_ >= 0) {
    const size_t want = std::min(kBatch, max - delivered);
    for (size_t i = 0; i < want; ++i) {
      vectors[i] = {receive_buffer_.data() + i * kMaxDatagram, kMaxDatagram};
      std::memset(&messages[i], 0, sizeof messages[i]);
      messages[i].msg_hdr.msg_iov = &vectors[i];
      messages[i].msg_hdr.msg_iovlen = 1;
      messages[i].msg_hdr.msg_name = senders[i].data();
      messages[i].msg_hdr.msg_namelen = static_cast<socklen_t>(senders[i].capacity());
    }
    const int got = ::recvmmsg(fd_, messages, static_cast<unsigned>(want), MSG_DONTWAIT, nullptr);
    if (got < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      if (errno == EINTR) continue;
      // An ICMP error for an earlier send (connection refused): the socket
      // is fine and the next call reads on.
      ++stats_.receive_errors;
      stats_.last_error = last_os_error();
      continue;
    }
    for (int i = 0; i < got; ++i) {
      senders[i].resize(messages[i].msg_hdr.msg_namelen);
      const size_t bytes = messages[i].msg_len;
      ++stats_.datagrams_received;
      stats_.bytes_received += bytes;
      handler(std::span<const uint8_t>(static_cast<const uint8_t*>(vectors[i].iov_base), bytes),
              senders[i]);
    }
    delivered += static_cast<size_t>(got);
    if (static_cast<size_t>(got) < want) break;  // nothing more waits
  }
#else
  Endpoint sender;
  while (delivered < max && fd_ >= 0) {
    socklen_t length = static_cast<socklen_t>(sender.capacity());
    const ssize_t bytes =
        ::recvfrom(fd_, receive_buffer_.data(), kMaxDatagram, 0, sender.data(), &length);
    if (bytes < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      if (errno == EINTR) continue;
      ++stats_.receive_errors;
      stats_.last_error = last_os_error();
      continue;
    }
    sender.resize(length);
    ++stats_.datagrams_received;
    stats_.bytes_received += static_cast<size_t>(bytes);
    handler(std::span<const uint8_t>(receive_buffer_.data(), static_cast<size_t>(bytes)), sender);
    ++delivered;
  }
#endif
  return delivered;
}

void PolledUdpSocket::queue_send(std::span<const uint8_t> bytes, const Endpoint& to) {
  if (fd_ < 0) return;
  queued_.push_back({queued_bytes_.size(), bytes.size(), to});
  queued_bytes_.insert(queued_bytes_.end(), bytes.begin(), bytes.end());
}

size_t PolledUdpSocket::flush_sends() {
  size_t sent = 0;
  size_t next = 0;
#if defined(__linux__)
  mmsghdr messages[kBatch];
  iovec vectors[kBatch];
  while (next < queued_.size() && fd_ >= 0) {
    const size_t count = std::min(kBatch, queued_.size() - next);
    for (size_t i = 0; i < count; ++i) {
      Queued& q = queued_[next + i];
      vectors[i] = {queued_bytes_.data() + q.offset, q.size};
      std::memset(&messages[i], 0, sizeof messages[i]);
      messages[i].msg_hdr.msg_iov = &vectors[i];
      messages[i].msg_hdr.msg_iovlen = 1;
      messages[i].msg_hdr.msg_name = q.to.data();
      messages[i].msg_hdr.msg_namelen = static_cast<socklen_t>(q.to.size());
    }
    const int done = ::sendmmsg(fd_, messages, static_cast<unsigned>(count), MSG_DONTWAIT);
    if (done < 0) {
      if (errno == EINTR) continue;
      // The first of the batch was refused: count it, drop it, go on. (A
      // short count means the one after the last sent failed; the next
      // call reports why.)
      ++stats_.send_errors;
      stats_.last_error = last_os_error();
      ++next;
      continue;
    }
    for (int i = 0; i < done; ++i) {
      ++stats_.datagrams_sent;
      stats_.bytes_sent += queued_[next + static_cast<size_t>(i)].size;
    }
    sent += static_cast<size_t>(done);
    next += static_cast<size_t>(done);
  }
#else
  for (; next < queued_.size() && fd_ >= 0; ++next) {
    const Queued& q = queued_[next];
    const ssize_t done = ::sendto(fd_, queued_bytes_.data() + q.offset, q.size, 0, q.to.data(),
                                  static_cast<socklen_t>(q.to.size()));
    if (done < 0 && errno == EINTR) {
      --next;
      continue;
    }
    if (done != static_cast<ssize_t>(q.size)) {
      ++stats_.send_errors;
      stats_.last_error = last_os_error();
      continue;
    }
    ++stats_.datagrams_sent;
    stats_.bytes_sent += q.size;
    ++sent;
  }
#endif
  queued_.clear();
  queued_bytes_.clear();
  return sent;
}

}  // namespace rwd::net
