// Where a server listens and a client connects: whether an address stays on this
// machine. `snooker serve` listens in plaintext only on such an address unless told
// otherwise (--insecure), and `snooker loadtest` sends load nowhere else.
#pragma once

#include <string>
#include <string_view>

namespace snooker::server {

/// True when `address` ("host:port", "[v6]:port", "unix:path" ...) can only be
/// reached from this machine: an IPv4 address in 127.0.0.0/8, ::1 (also as
/// ::ffff:127.x.y.z), "localhost", or a Unix domain socket ("unix:",
/// "unix-abstract:"). Everything else is not: a wildcard (0.0.0.0, [::], an empty
/// host), any other address or host name.
bool IsLoopbackAddress(std::string_view address);

/// Empty when `address` is "host:port" or "[v6]:port" with a port in [0, 65535]
/// (0: any free port), or a Unix socket; otherwise what is wrong. (gRPC takes port
/// 99999 as 34463.)
std::string CheckListenAddress(std::string_view address);

/// Empty when a client may call `target`: a gRPC target ("host:port", "[v6]:port",
/// with or without a "dns:", "ipv4:" or "ipv6:" scheme, a Unix socket, or a host
/// alone) whose port, when it names one, is in [1, 65535]; otherwise what is wrong.
/// (gRPC takes port 101815 as 36279 and -5 as 65531.)
std::string CheckConnectTarget(std::string_view target);

/// The host and port of "host:port" or "[v6]:port" (a valid listen address that is
/// not a Unix socket); false otherwise.
bool SplitHostPort(std::string_view address, std::string* host, int* port);

/// Why a server must not listen on `address` in plaintext (empty when it may):
/// without TLS and without `allow_insecure`, only a loopback address. `what` says
/// what it would do there ("listen", "serve HTTP").
std::string PlaintextRefusal(std::string_view address, bool tls, bool allow_insecure, std::string_view what);

}  // namespace snooker::server
