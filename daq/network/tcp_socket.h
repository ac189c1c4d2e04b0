#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace oscilab::daq {

/// A TCP socket (POSIX), closed on destruction. Only what the stream protocol needs: listen on
/// an address, accept and receive with a timeout (so a thread can notice it is asked to stop),
/// connect, and send everything.
class TcpSocket {
 public:
  TcpSocket() = default;
  explicit TcpSocket(int fd) : fd_(fd) {}
  ~TcpSocket();
  TcpSocket(TcpSocket&& other) noexcept;
  TcpSocket& operator=(TcpSocket&& other) noexcept;
  TcpSocket(const TcpSocket&) = delete;
  TcpSocket& operator=(const TcpSocket&) = delete;

  /// Listens on host:port (IPv4 address or "localhost"; port 0 picks a free one). Throws
  /// InputError naming the address on failure.
  static TcpSocket listen_on(const std::string& host, std::uint16_t port);
  /// Connects to host:port; throws InputError naming the address on failure.
  static TcpSocket connect_to(const std::string& host, std::uint16_t port);

  /// Waits up to timeout_ms for a connection; an invalid socket when none came.
  TcpSocket accept_for(int timeout_ms) const;
  /// Waits up to timeout_ms for data: bytes read (> 0), 0 when the peer closed, −1 on a timeout,
  /// −2 on an error.
  long receive_for(std::uint8_t* buffer, std::size_t size, int timeout_ms) const;
  /// Sends all bytes; false when the connection is gone.
  bool send_all(const std::uint8_t* bytes, std::size_t size) const;
  /// Waits up to timeout_ms until the socket takes bytes, then sends what it takes without
  /// blocking: bytes sent (> 0), −1 on a timeout (a receiver not reading), −2 when the connection
  /// is gone. A sender loops on it to notice it is asked to stop.
  long send_for(const std::uint8_t* bytes, std::size_t size, int timeout_ms) const;

  bool valid() const { return fd_ >= 0; }
  std::uint16_t local_port() const;
  std::string peer() const;  // "127.0.0.1:40312"
  /// Shuts the socket down (wakes a thread blocked on it) without closing the descriptor.
  void shutdown() const;
  void close();

 private:
  int fd_ = -1;
};

/// Splits "HOST:PORT" (the port required, 1..65535); throws InputError naming `what`.
void parse_host_port(const std::string& text, const std::string& what, std::string& host,
                     std::uint16_t& port);

}  // namespace oscilab::daq
