#include "cli/client.h"

#include <absl/base/internal/sysinfo.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/security/credentials.h>

#include <future>

#include "cli/commands.h"
#include "server/address.h"
#include "server/limits.h"
#include "server/read_file.h"
#include "server/request_id.h"

namespace snooker::cli {

std::set<std::string> ClientFlags(const std::string& target_flag) {
  return {target_flag, "tls-ca", "tls-cert", "tls-key", "tls-server-name", "deadline-ms"};
}

const char* ClientFlagsHelp() {
  return R"(Client (with --server):
  --server HOST:PORT     call a `snooker serve` there instead of computing here
  --tls-ca CA.pem        use TLS and trust server certificates signed by this CA
  --tls-cert CERT.pem    present this client certificate (with --tls-key), for a
  --tls-key KEY.pem      server that requires one (--tls-client-ca)
  --tls-server-name N    the name the server's certificate carries, when it is not
                         the host of --server
  --deadline-ms MS       the call's deadline, ms
)";
}

namespace {

bool ReadPem(const std::string& command, const std::string& flag, const std::string& path,
             std::string* pem, std::ostream& err) {
  std::string why;
  if (!server::ReadInputFile(path, pem, &why)) {
    err << command << ": --" << flag << " cannot read '" << path << "': " << why << "\n";
    return false;
  }
  return true;
}

// Runs, before this process opens its first connection, the one-time set-up in
// Abseil that can leave a stale errno behind in the middle of gRPC's connect.
//
// gRPC 1.51's TCP client (Debian 12's) calls connect() on a non-blocking socket and
// reads errno to tell "in progress" (EINPROGRESS, the usual answer) from a failure
// only after registering the socket with its poller (grpc_fd_create), which locks
// Abseil mutexes. The first time any absl::Mutex in a process is contended, Abseil
// measures the CPU's nominal frequency once (absl::base_internal::
// NominalCPUFrequency), first trying to read /sys/devices/system/cpu/cpu0/tsc_freq_khz,
// a file only some patched kernels provide; where it is missing (stock Linux
// kernels, the development machine's among them) the attempt leaves errno = ENOENT.
// When that first contention falls between connect() and the errno check, which
// happens when several threads connect at once (the load test's clients, each with
// a connection of its own), gRPC takes the connection for failed ("No such file or
// directory"), the channel stays in TRANSIENT_FAILURE for its reconnect backoff (a
// second or more), and every call made meanwhile fails at once with
//   UNAVAILABLE: failed to connect to all addresses; last error: UNKNOWN:
//   ipv4:127.0.0.1:PORT: No such file or directory
// (later gRPC releases save connect()'s errno at once). Done here, before any
// channel connects, the measurement cannot happen inside a connect. It costs a few
// milliseconds once (Abseil times short sleeps when the file is missing), which the
// first contended mutex would otherwise pay.
void SetUpBeforeTheFirstConnection() {
  static const double nominal_hz = absl::base_internal::NominalCPUFrequency();
  (void)nominal_hz;
}

}  // namespace

bool ClientOptionsFrom(Args& args, const std::string& command, const std::string& target_flag,
                       long default_deadline_ms, ClientOptions* options, std::ostream& err) {
  const auto target = args.Text(target_flag, "");
  const auto ca = args.Text("tls-ca", "");
  const auto cert = args.Text("tls-cert", "");
  const auto key = args.Text("tls-key", "");
  const auto name = args.Text("tls-server-name", "");
  const auto deadline = args.Integer("deadline-ms", default_deadline_ms, 1,
                                     server::limits::kMaxCallMsLimit);
  if (!args.error().empty()) return true;  // the caller reports it
  if (const std::string why = server::CheckConnectTarget(*target); !why.empty()) {
    err << command << ": --" << target_flag << ": " << why << "\n";
    return false;
  }
  options->target = *target;
  if (cert->empty() != key->empty()) {
    err << command << ": --tls-cert and --tls-key go together\n";
    return false;
  }
  options->tls = !ca->empty() || !cert->empty();
  if (!ca->empty() && !ReadPem(command, "tls-ca", *ca, &options->ca_pem, err)) return false;
  if (!cert->empty() && (!ReadPem(command, "tls-cert", *cert, &options->cert_pem, err) ||
                         !ReadPem(command, "tls-key", *key, &options->key_pem, err))) {
    return false;
  }
  options->server_name = *name;
  options->deadline = std::chrono::milliseconds(*deadline);
  return true;
}

std::shared_ptr<grpc::Channel> MakeChannel(const ClientOptions& options, bool own_connection) {
  SetUpBeforeTheFirstConnection();
  grpc::ChannelArguments arguments;
  // The server's answers are at most kMaxResponseBytes (plus its backstop's slack).
  arguments.SetMaxReceiveMessageSize(static_cast<int>(server::limits::kMaxResponseBytes + 4096));
  arguments.SetMaxSendMessageSize(static_cast<int>(server::limits::kMaxRequestBytes));
  if (own_connection) arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  if (!options.tls) {
    return grpc::CreateCustomChannel(options.target, grpc::InsecureChannelCredentials(), arguments);
  }
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = options.ca_pem;
  ssl.pem_private_key = options.key_pem;
  ssl.pem_cert_chain = options.cert_pem;
  if (!options.server_name.empty()) {
    arguments.SetSslTargetNameOverride(options.server_name);
  }
  return grpc::CreateCustomChannel(options.target, grpc::SslCredentials(ssl), arguments);
}

grpc::Status CheckHealth(const std::shared_ptr<grpc::Channel>& channel, const std::string& service,
                         std::chrono::milliseconds deadline, std::string* status) {
  // grpc.health.v1.HealthCheckRequest {string service = 1} by hand: the message is
  // one string field (tag 1, length-delimited), and the standard proto is not part
  // of this project's API.
  if (service.size() > 127) return {grpc::StatusCode::INVALID_ARGUMENT, "service name too long"};
  std::string bytes;
  bytes.push_back('\x0a');
  bytes.push_back(static_cast<char>(service.size()));
  bytes += service;
  grpc::GenericStub stub(channel);
  grpc::Slice slice(bytes);
  grpc::ByteBuffer request(&slice, 1), response;
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + deadline);
  std::promise<grpc::Status> done;
  stub.UnaryCall(&context, "/grpc.health.v1.Health/Check", grpc::StubOptions(), &request, &response,
                 [&](grpc::Status s) { done.set_value(std::move(s)); });
  grpc::Status st = done.get_future().get();
  if (!st.ok()) return st;
  // HealthCheckResponse {ServingStatus status = 1}: tag 0x08 and a varint (a
  // missing field is 0, UNKNOWN).
  std::vector<grpc::Slice> slices;
  std::string answer;
  if (response.Dump(&slices).ok()) {
    for (const grpc::Slice& s : slices) answer.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  int value = 0;
  if (answer.size() >= 2 && answer[0] == '\x08' && (answer[1] & 0x80) == 0) value = answer[1];
  static constexpr const char* kNames[] = {"UNKNOWN", "SERVING", "NOT_SERVING", "SERVICE_UNKNOWN"};
  *status = value >= 0 && value < 4 ? kNames[value] : "UNKNOWN";
  return st;
}

std::string NameCall(grpc::ClientContext* context) {
  std::string id = server::NewRequestId();
  context->AddMetadata(std::string(server::kRequestIdMetadata), id);
  return id;
}

int ReportCallError(const std::string& command, const std::string& target, const grpc::Status& status,
                    const std::string& request_id, std::ostream& err) {
  err << command << ": " << StatusCodeName(status.error_code()) << " from " << target << ": "
      << status.error_message() << " (request id " << request_id << ")\n";
  return status.error_code() == grpc::StatusCode::INVALID_ARGUMENT ? kExitUsage : kExitFailure;
}

}  // namespace snooker::cli
