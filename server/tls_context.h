// HTTPS's certificates in OpenSSL: the context's certificate, key and client CA from
// TlsOptions' PEM text, and, when the options name their files and a reload
// interval, the same read again from the files as they change, so that a rotated
// certificate is served without a restart (gRPC's side of the same is gRPC's own
// file watcher, server.cc).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>

#include <openssl/ssl.h>

namespace snooker::server {

struct TlsOptions;
struct TlsMaterial;

/// Sets up `ctx` for the server: TLS 1.2 or later, the certificate chain and key
/// (which must match), and with a client CA, client certificates required and
/// verified. False, with *why naming the part that does not load, on bad PEM.
bool SetUpTls(SSL_CTX& ctx, const TlsOptions& tls, std::string* why);

/// Empty, or why the PEM text of `tls` does not load (SetUpTls's reasons).
std::string CheckTlsText(const TlsOptions& tls);

/// When the first certificate of the PEM text `cert_chain_pem` (the leaf) expires, its
/// notAfter in s since the Unix epoch; nullopt when it does not load.
std::optional<std::int64_t> CertificateExpiry(const std::string& cert_chain_pem);

/// Reads TlsOptions' files again, at most once a reload interval, as a handshake
/// asks for them (SSL_CTX_set_cert_cb): a file whose modification time or size has
/// changed has all three read again (as the command line reads them: ReadInputFile),
/// and a set that loads (PEM, the key matching the certificate) is what later
/// handshakes present and verify clients by. A set that
/// does not load leaves the last good one in use and is said once in the log.
class TlsReloader {
 public:
  /// `log` (may be null) gets a line for each set taken or refused, under `log_mu`.
  TlsReloader(const TlsOptions& tls, std::ostream* log, std::mutex* log_mu);
  ~TlsReloader();
  TlsReloader(const TlsReloader&) = delete;
  TlsReloader& operator=(const TlsReloader&) = delete;

  /// Installs this on `ctx`: every handshake of its connections asks it.
  void Install(SSL_CTX& ctx);

  /// When the certificate that the next handshake presents expires (CertificateExpiry),
  /// the files read again first if a handshake would read them now: a set read again,
  /// or `start_expiry`, the context's own certificate's.
  std::optional<std::int64_t> Expiry(std::optional<std::int64_t> start_expiry);

 private:
  struct Stamp {
    long long mtime_ns = -1;
    long long size = -1;
    bool operator==(const Stamp&) const = default;
  };
  static Stamp StampOf(const std::string& path);
  static int OnCertificate(SSL* ssl, void* self);
  std::shared_ptr<const TlsMaterial> Current();
  void Say(const std::string& line);

  std::string files_[3];  // the certificate, its key, the client CA (empty: none)
  std::chrono::steady_clock::duration interval_;
  std::ostream* log_;
  std::mutex* log_mu_;
  std::mutex mu_;
  std::chrono::steady_clock::time_point next_check_;
  Stamp stamps_[3];
  std::shared_ptr<const TlsMaterial> material_;  // null: the context's own (the start's)
  std::string refused_;                          // the last refusal said, not to repeat it
};

}  // namespace snooker::server
