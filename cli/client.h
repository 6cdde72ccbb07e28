// The command line as a gRPC client (`snooker simulate --server`, `snooker plan
// --server`, `snooker loadtest`): the channel to a server, with TLS when asked, and
// the standard health check.
//
// Flags (kClientFlags): --server HOST:PORT, --tls-ca CA.pem (TLS, verifying the
// server against this CA), --tls-cert CERT.pem and --tls-key KEY.pem (a client
// certificate, for a server that requires one), --tls-server-name NAME (the name the
// server's certificate must carry, when it is not the host of --server),
// --deadline-ms MS.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>

#include "cli/args.h"
#include "server/grpc_service.h"

namespace snooker::cli {

struct ClientOptions {
  std::string target;  ///< "host:port"
  bool tls = false;
  std::string ca_pem, cert_pem, key_pem;  ///< TLS: roots (empty: the system's), client pair
  std::string server_name;               ///< TLS: name override ("" : the target's host)
  std::chrono::milliseconds deadline{30'000};
};

/// The valued flags of a client command (see the header comment).
/// `target_flag` is "server" (the default) or another name (loadtest's "target").
std::set<std::string> ClientFlags(const std::string& target_flag = "server");

/// Help text lines for the client flags, for a command's --help.
const char* ClientFlagsHelp();

/// The client options from parsed flags (`args` must have been built with
/// ClientFlags()); reads the PEM files. False with the reason on `err`, prefixed by
/// `command`. `default_deadline_ms` when --deadline-ms is not given.
bool ClientOptionsFrom(Args& args, const std::string& command, const std::string& target_flag,
                       long default_deadline_ms, ClientOptions* options, std::ostream& err);

/// A channel to options.target, TLS or plaintext, receiving answers up to the
/// server's largest. `own_connection`: a connection of its own, not shared with other
/// channels to the same target (a load test's clients).
std::shared_ptr<grpc::Channel> MakeChannel(const ClientOptions& options, bool own_connection = false);

/// The standard health check (grpc.health.v1.Health/Check) for `service`: OK and
/// the serving status ("SERVING", "NOT_SERVING", ...) in `status`, or the call's error.
grpc::Status CheckHealth(const std::shared_ptr<grpc::Channel>& channel, const std::string& service,
                         std::chrono::milliseconds deadline, std::string* status);

/// Names a call for the server's log with a new request id (server/request_id.h) and
/// returns it, for the command to name the call by too.
std::string NameCall(grpc::ClientContext* context);

/// Prints a failed call as "<command>: <CODE> from <target>: <message> (request id
/// <id>)" and returns the exit code (kExitUsage for INVALID_ARGUMENT, as the local
/// command; kExitFailure otherwise).
int ReportCallError(const std::string& command, const std::string& target, const grpc::Status& status,
                    const std::string& request_id, std::ostream& err);

/// gRPC's name of a status code (the server's, server/grpc_service.h).
using server::StatusCodeName;

}  // namespace snooker::cli
