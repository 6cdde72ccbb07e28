// The server's certificates in OpenSSL: HTTPS's context (the certificate, key and
// client CA from TlsOptions' PEM text) and, when the options name their files and a
// reload interval, the same read again from the files as they change, so that a
// rotated certificate is served without a restart: one reader of the files
// (TlsReloader), which HTTPS asks at its handshakes and gRPC through in-memory files
// that hold only whole sets (GrpcTlsFiles).
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <thread>

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
/// does not load leaves the last good one in use and is said once in the log. A
/// server has one, shared by its listeners, so that the files are read and each set
/// is said once.
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

  /// The set in use, after reading the files again if they are due (or at once, with
  /// `now`); null while it is the start's (TlsOptions' text).
  std::shared_ptr<const TlsMaterial> Current(bool now = false);

  /// Says in the log that the set in use is kept because of `why` (what failed after
  /// the files were read), once while `why` stays the same.
  void SayKept(const std::string& why);

  /// How often the files are read again at most.
  std::chrono::steady_clock::duration interval() const { return interval_; }

 private:
  struct Stamp {
    long long mtime_ns = -1;
    long long size = -1;
    bool operator==(const Stamp&) const = default;
  };
  static Stamp StampOf(const std::string& path);
  static int OnCertificate(SSL* ssl, void* self);
  void Say(const std::string& line);
  void SayKeptLocked(const std::string& why);  // under mu_

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

/// The files gRPC's certificate watcher (FileWatcherCertificateProvider) reads when
/// certificates are reloaded. That watcher takes whatever the files hold at its check:
/// a key written before its certificate, or one that is not the certificate's, is then
/// served and no handshake succeeds; a FIFO in place of a file is opened and waited on,
/// and the server's shutdown waits with it. So gRPC does not read the operator's files.
/// The server's TlsReloader reads them, asked every reload interval on a thread of
/// this, and each set it takes is written to in-memory files (memfd_create) that gRPC
/// reads as /proc/self/fd/N: the certificate chain and its key in one file, replaced
/// whole (dup3) so that gRPC never reads half a set, and the client CA in another. A
/// set that does not load leaves the files, and gRPC's handshakes, as they were.
class GrpcTlsFiles {
 public:
  /// The files, holding `tls`'s text (the start's set, which must load), and the
  /// thread that asks `reloader` (of `tls`'s files) every interval; null with *why if
  /// the system gives no such files (no memfd, no /proc).
  static std::unique_ptr<GrpcTlsFiles> Start(const TlsOptions& tls, std::shared_ptr<TlsReloader> reloader,
                                             std::string* why);
  ~GrpcTlsFiles();  // stops the thread and closes the files: destroy after gRPC's server
  GrpcTlsFiles(const GrpcTlsFiles&) = delete;
  GrpcTlsFiles& operator=(const GrpcTlsFiles&) = delete;

  /// The certificate chain and its key, both in this one file.
  const std::string& identity_file() const { return identity_path_; }
  /// The client CA's file; empty when clients are not asked for a certificate.
  const std::string& ca_file() const { return ca_path_; }

 private:
  explicit GrpcTlsFiles(std::shared_ptr<TlsReloader> reloader);
  void Watch();
  /// Writes `text` to a new in-memory file and puts it in place of `*fd` (the first
  /// time, makes `*fd` that file); false with *why.
  static bool Replace(const std::string& text, int* fd, std::string* why);

  std::shared_ptr<TlsReloader> reloader_;
  int identity_fd_ = -1, ca_fd_ = -1;
  std::string identity_path_, ca_path_;
  std::shared_ptr<const TlsMaterial> written_;  // the set in the files (null: the start's)
  std::mutex mu_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;  // last: it uses the members above
};

}  // namespace snooker::server
