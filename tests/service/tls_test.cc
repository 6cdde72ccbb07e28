// Security of `snooker serve`: plaintext only on loopback unless
// asked for explicitly; TLS, and mutual TLS with a client CA; a plaintext client, a
// client that does not trust the server and a client without the right certificate
// are refused. The certificates are made per test process by scripts/dev-certs
// (a throwaway CA with openssl; nothing is committed).
#include <grpcpp/grpcpp.h>
#include <grpcpp/security/credentials.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include "health.grpc.pb.h"
#include "server/address.h"
#include "server/server.h"
#include "tests/support/cli_support.h"
#include "tests/service/requests.h"
#include "tests/service/server_support.h"
#include "tests/support/text.h"

namespace snooker::server {
namespace {

TEST(LoopbackAddressTest, OnlyAddressesOfThisMachineAreLoopback) {
  for (const char* a : {"127.0.0.1:50051", "127.1.2.3:0", "localhost:50051", "[::1]:50051",
                        "[::ffff:127.0.0.1]:1", "unix:/tmp/snooker.sock", "ipv4:127.0.0.1:80"}) {
    EXPECT_TRUE(IsLoopbackAddress(a)) << a;
  }
  for (const char* a : {"0.0.0.0:50051", "[::]:50051", ":50051", "10.0.0.1:50051",
                        "192.168.1.2:1", "example.com:50051", "128.0.0.1:1", "[::2]:1",
                        "127.0.0.1", "::1:50051", "localhost.evil.com:1", ""}) {
    EXPECT_FALSE(IsLoopbackAddress(a)) << a;
  }
}

TEST(LoopbackAddressTest, ListenAddressesNeedAPortInRange) {
  EXPECT_EQ(CheckListenAddress("127.0.0.1:0"), "");
  EXPECT_EQ(CheckListenAddress("[::]:65535"), "");
  EXPECT_EQ(CheckListenAddress("unix:/tmp/x.sock"), "");
  EXPECT_TRUE(Mentions(CheckListenAddress("127.0.0.1:99999"), "not in [0, 65535]"));
  EXPECT_TRUE(Mentions(CheckListenAddress("127.0.0.1:http"), "not in [0, 65535]"));
  EXPECT_TRUE(Mentions(CheckListenAddress("127.0.0.1"), "is not HOST:PORT"));
}

// A client's port is checked before gRPC, which would take it modulo 65536.
TEST(LoopbackAddressTest, ClientTargetsNeedAPortInRangeWhenTheyNameOne) {
  for (const char* good : {"127.0.0.1:1", "[::1]:65535", "localhost:50051", "dns:///example.com:443",
                           "ipv4:127.0.0.1:50051", "unix:/tmp/x.sock", "example.com", ""}) {
    EXPECT_EQ(CheckConnectTarget(good), "") << good;
  }
  EXPECT_EQ(CheckConnectTarget("127.0.0.1:101815"), "port '101815' of '127.0.0.1:101815' is not in [1, 65535]");
  for (const char* bad : {"127.0.0.1:0", "127.0.0.1:-5", "127.0.0.1:65536", "dns:///localhost:99999",
                          "[::1]:http", "localhost:"}) {
    EXPECT_TRUE(Mentions(CheckConnectTarget(bad), "is not in [1, 65535]")) << bad;
  }
  const cli_support::RunResult r = cli_support::RunCli("plan --server 127.0.0.1:101815 --table builtin:black");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_TRUE(Mentions(r.err, "--server: port '101815' of '127.0.0.1:101815' is not in [1, 65535]")) << r.err;
  const cli_support::RunResult l = cli_support::RunCli("loadtest --target 127.0.0.1:-5 --concurrency 1 --requests 1");
  EXPECT_EQ(l.exit_code, 2) << l.out;
  EXPECT_TRUE(Mentions(l.err, "--target: port '-5' of '127.0.0.1:-5' is not in [1, 65535]")) << l.err;
}

std::string Read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

class TlsTest : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = cli_support::TempPath("snooker_certs");
    const std::string cmd = std::string(SNOOKER_DEV_CERTS) + " " + dir_ + " >/dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  static std::string Pem(const std::string& name) { return Read(dir_ + "/" + name); }
  static std::string Path(const std::string& name) { return dir_ + "/" + name; }

  static TlsOptions ServerTls(bool require_client_certificates) {
    TlsOptions tls;
    tls.cert_chain_pem = Pem("server.pem");
    tls.private_key_pem = Pem("server.key");
    if (require_client_certificates) tls.client_ca_pem = Pem("ca.pem");
    return tls;
  }

  std::unique_ptr<Server> Start(ServerOptions options, std::string* error = nullptr) {
    std::string e;
    auto s = Server::Start(options, &e);
    if (error != nullptr) *error = e;
    return s;
  }

  // A Collide call to 127.0.0.1:port with these credentials (5 s deadline).
  static grpc::Status Call(int port, const std::shared_ptr<grpc::ChannelCredentials>& creds) {
    auto stub = v1::ShotPlanner::NewStub(
        grpc::CreateChannel("127.0.0.1:" + std::to_string(port), creds));
    v1::CollideResponse resp;
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
    return stub->Collide(&ctx, testing_requests::PaperCollide(), &resp);
  }

  static std::shared_ptr<grpc::ChannelCredentials> Tls(const std::string& ca,
                                                       const std::string& client = "") {
    grpc::SslCredentialsOptions o;
    o.pem_root_certs = Pem(ca);
    if (!client.empty()) {
      o.pem_cert_chain = Pem(client + ".pem");
      o.pem_private_key = Pem(client + ".key");
    }
    return grpc::SslCredentials(o);
  }

  static std::string dir_;
};
std::string TlsTest::dir_;

TEST_F(TlsTest, PlaintextIsRefusedOffLoopbackUnlessAskedFor) {
  for (const char* address : {"0.0.0.0:0", "[::]:0"}) {
    ServerOptions o;
    o.address = address;
    std::string error;
    EXPECT_EQ(Start(o, &error), nullptr) << address;
    EXPECT_TRUE(Mentions(error, std::string("refusing to listen on ") + address +
                                    " in plaintext: it is not a loopback address"))
        << error;
    o.allow_insecure = true;
    auto s = Start(o, &error);
    ASSERT_NE(s, nullptr) << error;
    EXPECT_TRUE(Call(s->port(), grpc::InsecureChannelCredentials()).ok());
  }
}

TEST_F(TlsTest, ATlsServerAnswersATlsClientOnAnyAddress) {
  ServerOptions o;
  o.address = "0.0.0.0:0";  // allowed with TLS
  o.tls = ServerTls(false);
  std::string error;
  auto s = Start(o, &error);
  ASSERT_NE(s, nullptr) << error;
  const grpc::Status st = Call(s->port(), Tls("ca.pem"));
  EXPECT_TRUE(st.ok()) << st.error_message();
  // Health through TLS.
  auto health = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel("127.0.0.1:" + std::to_string(s->port()), Tls("ca.pem")));
  grpc::health::v1::HealthCheckRequest req;
  req.set_service(kServiceName);
  grpc::health::v1::HealthCheckResponse resp;
  grpc::ClientContext ctx;
  ASSERT_TRUE(health->Check(&ctx, req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

TEST_F(TlsTest, APlaintextClientIsRefused) {
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(false);
  auto s = Start(o);
  ASSERT_NE(s, nullptr);
  const grpc::Status st = Call(s->port(), grpc::InsecureChannelCredentials());
  EXPECT_EQ(st.error_code(), grpc::StatusCode::UNAVAILABLE) << st.error_message();
  EXPECT_EQ(s->counts().received, 0);  // no call reached the service
}

TEST_F(TlsTest, AClientThatDoesNotTrustTheServerFails) {
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(false);
  auto s = Start(o);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(Call(s->port(), Tls("other-ca.pem")).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(s->counts().received, 0);
}

TEST_F(TlsTest, MutualTlsTakesOnlyClientsWithACertificateFromItsCa) {
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(true);
  auto s = Start(o);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(Call(s->port(), Tls("ca.pem")).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(Call(s->port(), Tls("ca.pem", "other-client")).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(s->counts().received, 0);
  const grpc::Status st = Call(s->port(), Tls("ca.pem", "client"));
  EXPECT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(s->counts().received, 1);
}

TEST_F(TlsTest, AKeyThatDoesNotLoadIsAnErrorNotAServer) {
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(false);
  o.tls->private_key_pem = Pem("client.key");  // not the certificate's key
  std::string error;
  EXPECT_EQ(Start(o, &error), nullptr);
  EXPECT_TRUE(Mentions(error, "cannot listen on 127.0.0.1:0 with TLS: the key does not match the certificate"))
      << error;
  o.tls->private_key_pem.clear();
  EXPECT_EQ(Start(o, &error), nullptr);
  EXPECT_TRUE(Mentions(error, "TLS needs both a certificate and its private key")) << error;
}

TEST_F(TlsTest, ARotatedCertificateAndClientCaAreServedWithoutARestart) {
  server_support::RotatingCertificates certs(cli_support::TempPath("snooker_grpc_rotation"));
  certs.Serve(Path("server.pem"), Path("server.key"), Path("ca.pem"));
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(true);
  o.tls->reload_interval = std::chrono::seconds(1);
  o.tls->cert_chain_file = certs.File("cert.pem");
  o.tls->private_key_file = certs.File("key.pem");
  o.tls->client_ca_file = certs.File("ca.pem");
  std::ostringstream log;
  o.log = &log;
  std::string error;
  auto s = Start(o, &error);
  ASSERT_NE(s, nullptr) << error;
  EXPECT_TRUE(Call(s->port(), Tls("ca.pem", "client")).ok());
  EXPECT_EQ(Call(s->port(), Tls("other-ca.pem", "other-client")).error_code(), grpc::StatusCode::UNAVAILABLE);

  // The server's certificate and the CA of its clients both rotated to another CA.
  certs.Serve(Path("other-server.pem"), Path("other-server.key"), Path("other-ca.pem"));
  EXPECT_TRUE(server_support::Eventually(std::chrono::seconds(15), [&] {
    return Call(s->port(), Tls("other-ca.pem", "other-client")).ok();
  }));
  EXPECT_EQ(Call(s->port(), Tls("ca.pem", "client")).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(Call(s->port(), Tls("other-ca.pem", "client")).error_code(), grpc::StatusCode::UNAVAILABLE);

  // A set whose key is not its certificate's is not taken: the last good set is
  // served through it, and once a whole set is back, that one.
  certs.Serve(Path("server.pem"), Path("other-server.key"), Path("ca.pem"));
  for (int i = 0; i < 6; ++i) {  // three reload intervals, the server's and gRPC's
    EXPECT_TRUE(Call(s->port(), Tls("other-ca.pem", "other-client")).ok()) << i;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  EXPECT_FALSE(Call(s->port(), Tls("ca.pem", "client")).ok());
  certs.Serve(Path("server.pem"), Path("server.key"), Path("ca.pem"));
  EXPECT_TRUE(server_support::Eventually(std::chrono::seconds(15), [&] {
    return Call(s->port(), Tls("ca.pem", "client")).ok();
  }));
  s->Shutdown(std::chrono::milliseconds(0));
  EXPECT_EQ(Occurrences(log.str(), "snooker: tls kept the certificate in use; its files changed but the "
                                   "key does not match the certificate"),
            1)
      << log.str();
  EXPECT_EQ(Occurrences(log.str(), "snooker: tls serves the certificate read again from " +
                                       certs.File("cert.pem")),
            2)
      << log.str();
}

// gRPC's own watcher would open a FIFO and wait on it, and the server's shutdown
// with it; the server's reader refuses what is not a regular file.
TEST_F(TlsTest, AFifoInPlaceOfAKeyIsRefusedNotWaitedOn) {
  server_support::RotatingCertificates certs(cli_support::TempPath("snooker_grpc_fifo"));
  certs.Serve(Path("server.pem"), Path("server.key"));
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(false);
  o.tls->reload_interval = std::chrono::seconds(1);
  o.tls->cert_chain_file = certs.File("cert.pem");
  o.tls->private_key_file = certs.File("key.pem");
  std::ostringstream log;
  o.log = &log;
  std::string error;
  auto s = Start(o, &error);
  ASSERT_NE(s, nullptr) << error;
  EXPECT_TRUE(Call(s->port(), Tls("ca.pem")).ok());
  const std::string key = certs.File("key.pem");
  ASSERT_EQ(std::remove(key.c_str()), 0);
  ASSERT_EQ(mkfifo(key.c_str(), 0600), 0);
  for (int i = 0; i < 5; ++i) {
    EXPECT_TRUE(Call(s->port(), Tls("ca.pem")).ok()) << i;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  auto stopped = std::async(std::launch::async, [&] { s->Shutdown(std::chrono::milliseconds(0)); });
  const bool in_time = stopped.wait_for(std::chrono::seconds(20)) == std::future_status::ready;
  EXPECT_TRUE(in_time) << "the shutdown waits on the FIFO";
  // Lets a reader that waits on the FIFO go on, as often as it opens it again, so
  // that the test ends.
  for (int i = 0; i < 600 && stopped.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready; ++i) {
    const int fd = open(key.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) close(fd);
  }
  stopped.wait();
  EXPECT_TRUE(Mentions(log.str(), "tls kept the certificate in use; its files changed but cannot read '" +
                                      key + "': is a FIFO (named pipe), not a regular file"))
      << log.str();
}

TEST_F(TlsTest, ReloadingNeedsTheFilesAndAnIntervalInRange) {
  ServerOptions o;
  o.address = "127.0.0.1:0";
  o.tls = ServerTls(true);
  o.tls->reload_interval = std::chrono::seconds(60);
  std::string error;
  EXPECT_EQ(Start(o, &error), nullptr);
  EXPECT_TRUE(Mentions(error, "reloading TLS needs the files of the certificate and its key")) << error;
  o.tls->cert_chain_file = Path("server.pem");
  o.tls->private_key_file = Path("server.key");
  EXPECT_EQ(Start(o, &error), nullptr);
  EXPECT_TRUE(Mentions(error, "with a client CA needs its file")) << error;
  o.tls->client_ca_file = Path("ca.pem");
  o.tls->reload_interval = std::chrono::seconds(limits::kMaxTlsReloadSeconds + 1);
  EXPECT_EQ(Start(o, &error), nullptr);
  EXPECT_TRUE(Mentions(error, "the TLS reload interval 86401 s is outside [0, 86400] s")) << error;

  using cli_support::RunCli;
  cli_support::RunResult r = RunCli("serve --tls-reload-s 60");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "--tls-reload-s needs --tls-cert and --tls-key")) << r.err;
  r = RunCli("serve --tls-reload-s 86401 --tls-cert " + Path("server.pem") + " --tls-key " + Path("server.key"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "tls-reload-s")) << r.err;
}

TEST_F(TlsTest, TheCommandLineServesAndCallsWithTls) {
  using cli_support::RunCli;
  // serve refuses plaintext off loopback, and half a TLS configuration.
  cli_support::RunResult r = RunCli("serve --address 0.0.0.0:0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(Mentions(r.err, "refusing to listen on 0.0.0.0:0 in plaintext")) << r.err;
  r = RunCli("serve --tls-cert " + Path("server.pem"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "--tls-cert and --tls-key go together")) << r.err;
  r = RunCli("serve --tls-cert /nonexistent.pem --tls-key " + Path("server.key"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(Mentions(r.err, "--tls-cert cannot read '/nonexistent.pem'")) << r.err;
  r = RunCli("serve --insecure --tls-cert " + Path("server.pem") + " --tls-key " + Path("server.key"));
  EXPECT_EQ(r.exit_code, 2);

  // snooker serve with mutual TLS (its files watched for rotation); snooker simulate
  // --server as its client.
  r = RunCli("serve --address 127.0.0.1:0 --tls-reload-s 60 --tls-cert " + Path("server.pem") + " --tls-key " +
             Path("server.key") + " --tls-client-ca " + Path("ca.pem") +
             " > " + Path("serve.out") + " & pid=$!; " + cli_support::kWaitForPort(Path("serve.out")) +
             SNOOKER_CLI_PATH +
             " simulate --table " +
             cli_support::TempFile("tls_table.json",
                                   R"({"balls": [{"id": "cue", "kind": "CUE", "position": {"x": 0.9, "y": 0.6}}]})") +
             " --shot " + cli_support::TempFile("tls_shot.json", R"({"speed": 1, "headingDeg": 90})") +
             // 127.0.0.1 and the name the certificate carries: no name lookup (c-ares
             // leaks a few bytes per process, which LeakSanitizer reports).
             " --server 127.0.0.1:$port --tls-server-name localhost --tls-ca " + Path("ca.pem") +
             " --tls-cert " +
             Path("client.pem") + " --tls-key " + Path("client.key") +
             "; echo simulate_rc=$?; kill -TERM $pid; wait $pid; echo serve_rc=$?");
  EXPECT_TRUE(Mentions(r.out, "status: at rest")) << r.out << r.err;
  EXPECT_TRUE(Mentions(r.out, "simulate_rc=0")) << r.out;
  EXPECT_TRUE(Mentions(r.out, "serve_rc=0")) << r.out;
  EXPECT_TRUE(Mentions(Read(Path("serve.out")), "TLS with client certificates"));
}

}  // namespace
}  // namespace snooker::server
