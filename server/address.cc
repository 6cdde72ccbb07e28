#include "server/address.h"

#include <arpa/inet.h>

#include <cstring>
#include <string>

namespace snooker::server {
namespace {

// The host of "host:port" or "[host]:port" (the port is required), or nothing.
bool SplitHost(std::string_view address, std::string_view* host) {
  if (address.starts_with("[")) {
    const std::size_t close = address.find(']');
    if (close == std::string_view::npos || close + 1 >= address.size() || address[close + 1] != ':') {
      return false;
    }
    *host = address.substr(1, close - 1);
    return true;
  }
  const std::size_t colon = address.rfind(':');
  if (colon == std::string_view::npos) return false;
  *host = address.substr(0, colon);
  // An IPv6 address needs its brackets when a port follows.
  return host->find(':') == std::string_view::npos;
}

// The value of a port of one to five digits, or -1.
long PortValue(std::string_view port) {
  long value = 0;
  bool digits = !port.empty() && port.size() <= 5;
  for (char c : port) {
    digits = digits && c >= '0' && c <= '9';
    if (digits) value = value * 10 + (c - '0');
  }
  return digits ? value : -1;
}

// `address` without a leading "ipv4:", "ipv6:", "dns:///" or "dns:".
std::string_view WithoutScheme(std::string_view address) {
  for (std::string_view scheme : {"ipv4:", "ipv6:", "dns:///", "dns:"}) {
    if (address.starts_with(scheme)) return address.substr(scheme.size());
  }
  return address;
}

}  // namespace

std::string CheckConnectTarget(std::string_view target) {
  if (target.starts_with("unix:") || target.starts_with("unix-abstract:")) return "";
  const std::string_view address = WithoutScheme(target);
  std::string_view host;
  if (!SplitHost(address, &host)) return "";  // a host alone: gRPC's default port
  const std::string_view port = address.substr(address.rfind(':') + 1);
  const long value = PortValue(port);
  if (value < 1 || value > 65535) {
    return "port '" + std::string(port) + "' of '" + std::string(target) + "' is not in [1, 65535]";
  }
  return "";
}

std::string CheckListenAddress(std::string_view address) {
  if (address.starts_with("unix:") || address.starts_with("unix-abstract:")) return "";
  std::string_view host;
  if (!SplitHost(address, &host)) {
    return "address '" + std::string(address) + "' is not HOST:PORT (an IPv6 host in brackets)";
  }
  const std::string_view port = address.substr(address.rfind(':') + 1);
  const long value = PortValue(port);
  if (value < 0 || value > 65535) {
    return "port '" + std::string(port) + "' of '" + std::string(address) + "' is not in [0, 65535]";
  }
  return "";
}

bool SplitHostPort(std::string_view address, std::string* host, int* port) {
  std::string_view h;
  if (address.starts_with("unix:") || address.starts_with("unix-abstract:") ||
      !CheckListenAddress(address).empty() || !SplitHost(address, &h)) {
    return false;
  }
  *host = std::string(h);
  *port = std::stoi(std::string(address.substr(address.rfind(':') + 1)));
  return true;
}

std::string PlaintextRefusal(std::string_view address, bool tls, bool allow_insecure, std::string_view what) {
  if (tls || allow_insecure || IsLoopbackAddress(address)) return "";
  return "refusing to " + std::string(what) + " on " + std::string(address) +
         " in plaintext: it is not a loopback address. Give a TLS certificate and key "
         "(--tls-cert, --tls-key), or --insecure for a trusted network";
}

bool IsLoopbackAddress(std::string_view address) {
  if (address.starts_with("unix:") || address.starts_with("unix-abstract:")) return true;
  address = WithoutScheme(address);
  std::string_view host;
  if (!SplitHost(address, &host) || host.empty()) return false;
  if (host == "localhost") return true;
  const std::string h(host);
  in_addr v4{};
  if (inet_pton(AF_INET, h.c_str(), &v4) == 1) {
    return (ntohl(v4.s_addr) >> 24) == 127;
  }
  in6_addr v6{};
  if (inet_pton(AF_INET6, h.c_str(), &v6) == 1) {
    if (IN6_IS_ADDR_LOOPBACK(&v6)) return true;
    return IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127;
  }
  return false;
}

}  // namespace snooker::server
