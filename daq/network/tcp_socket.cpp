#include "daq/network/tcp_socket.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

sockaddr_in resolve(const std::string& host, std::uint16_t port, const std::string& what) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  const std::string name = host == "localhost" ? "127.0.0.1" : host;
  if (inet_pton(AF_INET, name.c_str(), &address.sin_addr) == 1) return address;
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(name.c_str(), nullptr, &hints, &found) != 0 || found == nullptr) {
    throw InputError(what + ": cannot resolve host \"" + host + "\"");
  }
  address.sin_addr = reinterpret_cast<sockaddr_in*>(found->ai_addr)->sin_addr;
  freeaddrinfo(found);
  return address;
}

std::string address_text(const std::string& host, std::uint16_t port) {
  return host + ":" + std::to_string(port);
}

}  // namespace

TcpSocket::~TcpSocket() { close(); }

TcpSocket::TcpSocket(TcpSocket&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

TcpSocket& TcpSocket::operator=(TcpSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

void TcpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void TcpSocket::shutdown() const {
  if (fd_ >= 0) ::shutdown(fd_, SHUT_RDWR);
}

TcpSocket TcpSocket::listen_on(const std::string& host, std::uint16_t port) {
  const std::string where = "listen on " + address_text(host, port);
  const sockaddr_in address = resolve(host, port, where);
  TcpSocket socket(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!socket.valid()) throw InputError(where + ": " + std::strerror(errno));
  const int yes = 1;
  setsockopt(socket.fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  if (::bind(socket.fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
      ::listen(socket.fd_, 4) != 0) {
    throw InputError(where + ": " + std::strerror(errno));
  }
  return socket;
}

TcpSocket TcpSocket::connect_to(const std::string& host, std::uint16_t port) {
  const std::string where = "connect to " + address_text(host, port);
  const sockaddr_in address = resolve(host, port, where);
  TcpSocket socket(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!socket.valid()) throw InputError(where + ": " + std::strerror(errno));
  if (::connect(socket.fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    throw InputError(where + ": " + std::strerror(errno));
  }
  const int yes = 1;  // blocks are small and latency matters: no Nagle delay
  setsockopt(socket.fd_, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  return socket;
}

TcpSocket TcpSocket::accept_for(int timeout_ms) const {
  pollfd waiting{fd_, POLLIN, 0};
  if (::poll(&waiting, 1, timeout_ms) <= 0) return TcpSocket();
  TcpSocket peer(::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC));
  if (peer.valid()) {
    const int yes = 1;
    setsockopt(peer.fd_, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
  }
  return peer;
}

long TcpSocket::receive_for(std::uint8_t* buffer, std::size_t size, int timeout_ms) const {
  pollfd waiting{fd_, POLLIN, 0};
  const int ready = ::poll(&waiting, 1, timeout_ms);
  if (ready == 0) return -1;
  if (ready < 0) return errno == EINTR ? -1 : -2;
  const ssize_t got = ::recv(fd_, buffer, size, 0);
  if (got < 0) return errno == EINTR || errno == EAGAIN ? -1 : -2;
  return static_cast<long>(got);
}

bool TcpSocket::send_all(const std::uint8_t* bytes, std::size_t size) const {
  while (size > 0) {
    const ssize_t sent = ::send(fd_, bytes, size, MSG_NOSIGNAL);
    if (sent < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    bytes += sent;
    size -= static_cast<std::size_t>(sent);
  }
  return true;
}

long TcpSocket::send_for(const std::uint8_t* bytes, std::size_t size, int timeout_ms) const {
  pollfd waiting{fd_, POLLOUT, 0};
  const int ready = ::poll(&waiting, 1, timeout_ms);
  if (ready == 0) return -1;
  if (ready < 0) return errno == EINTR ? -1 : -2;
  const ssize_t sent = ::send(fd_, bytes, size, MSG_NOSIGNAL | MSG_DONTWAIT);
  if (sent > 0) return static_cast<long>(sent);
  if (sent == 0 || errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK) return -1;
  return -2;
}

std::uint16_t TcpSocket::local_port() const {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) return 0;
  return ntohs(address.sin_port);
}

std::string TcpSocket::peer() const {
  sockaddr_in address{};
  socklen_t length = sizeof address;
  if (getpeername(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) return "?";
  char text[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &address.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(ntohs(address.sin_port));
}

void parse_host_port(const std::string& text, const std::string& what, std::string& host,
                     std::uint16_t& port) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    throw InputError(what + ": \"" + text + "\" is not HOST:PORT");
  }
  host = text.substr(0, colon);
  const std::string digits = text.substr(colon + 1);
  char* end = nullptr;
  const long value = std::strtol(digits.c_str(), &end, 10);
  if (*end != '\0' || value < 1 || value > 65535) {
    throw InputError(what + ": port \"" + digits + "\" is not within 1..65535");
  }
  port = static_cast<std::uint16_t>(value);
}

}  // namespace oscilab::daq
