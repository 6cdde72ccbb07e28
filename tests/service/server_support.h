// An in-process server on a free loopback port and a stub to it, for the service
// tests that call it through gRPC (and for the command-line tests that point the
// `snooker` binary at it).
#pragma once

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <streambuf>
#include <string>
#include <thread>

#include "server/server.h"
#include "snooker/v1/service.grpc.pb.h"

namespace snooker::server_support {

/// A plan's shots as bytes, to compare two answers shot for shot.
inline std::string ShotsOf(const v1::PlanResponse& r) {
  std::string out;
  for (const v1::PlannedShot& s : r.shots()) out += s.SerializeAsString() + "|";
  return out;
}

/// Waits, at most `timeout`, until `server` has received at least `received` calls
/// and answered every call it received; returns its counts as last read.
inline server::CallCounts WaitUntilAnswered(const server::Server& server, std::int64_t received,
                                            std::chrono::steady_clock::duration timeout) {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  server::CallCounts c = server.counts();
  while ((c.received < received || c.in_flight() > 0) && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    c = server.counts();
  }
  return c;
}

/// True once `ok` holds, trying every 100 ms for at most `timeout`.
inline bool Eventually(std::chrono::steady_clock::duration timeout, const std::function<bool()>& ok) {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (!ok()) {
    if (std::chrono::steady_clock::now() >= give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

/// A server's TLS files as a certificate rotator keeps them (a mounted Kubernetes
/// secret, for one): DIR/live is a symbolic link to the version in use, and Serve
/// writes a new version beside it and renames a new link over `live`, so that a
/// reader sees the old set or the new one, never half of each.
class RotatingCertificates {
 public:
  explicit RotatingCertificates(std::string dir) : dir_(std::move(dir)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  /// Makes copies of these files the set in use: cert.pem, key.pem and, when given,
  /// ca.pem.
  void Serve(const std::string& cert, const std::string& key, const std::string& ca = "") {
    namespace fs = std::filesystem;
    const std::string version = "v" + std::to_string(++versions_);
    fs::create_directories(dir_ + "/" + version);
    fs::copy_file(cert, dir_ + "/" + version + "/cert.pem");
    fs::copy_file(key, dir_ + "/" + version + "/key.pem");
    if (!ca.empty()) fs::copy_file(ca, dir_ + "/" + version + "/ca.pem");
    fs::create_directory_symlink(version, dir_ + "/next");
    fs::rename(dir_ + "/next", dir_ + "/live");
  }
  /// The path a server reads `name` at.
  std::string File(const std::string& name) const { return dir_ + "/live/" + name; }

 private:
  std::string dir_;
  int versions_ = 0;
};

/// A stream buffer that takes no character: every write through it fails (a log
/// on a full disk).
struct RefusingBuffer : std::streambuf {
  int_type overflow(int_type) override { return traits_type::eof(); }
};

struct TestServer {
  /// Starts a server with `options` on 127.0.0.1 (any free port) unless
  /// options.address names another; logs into `log`.
  explicit TestServer(server::ServerOptions options = {}) {
    if (options.address == server::ServerOptions().address) options.address = "127.0.0.1:0";
    options.log = &log;
    std::string error;
    server = server::Server::Start(options, &error);
    EXPECT_NE(server, nullptr) << error;
    if (server == nullptr) return;
    target = "127.0.0.1:" + std::to_string(server->port());
    if (!options.tls) {
      channel = grpc::CreateChannel(target, grpc::InsecureChannelCredentials());
      stub = v1::ShotPlanner::NewStub(channel);
    }
  }
  ~TestServer() {
    if (server) server->Shutdown(std::chrono::milliseconds(0));
  }
  std::ostringstream log;  // written under the service's lock; read after calls end
  std::unique_ptr<server::Server> server;
  std::string target;  ///< "127.0.0.1:PORT"
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<v1::ShotPlanner::Stub> stub;
};

}  // namespace snooker::server_support
