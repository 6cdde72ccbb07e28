#include "server/tls_context.h"

#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <utility>

#include "server/log_line.h"
#include "server/read_file.h"
#include "server/server.h"

namespace snooker::server {

// A certificate set as a handshake takes it: the leaf, the rest of its chain, its key,
// and the client CA (its certificates to verify by, their names to ask for).
struct TlsMaterial {
  X509* leaf = nullptr;
  STACK_OF(X509)* chain = sk_X509_new_null();
  EVP_PKEY* key = nullptr;
  X509_STORE* ca_store = nullptr;  // null: clients are not asked for a certificate
  STACK_OF(X509_NAME)* ca_names = nullptr;
  std::optional<std::int64_t> expiry;  // the leaf's notAfter, Unix s
  std::string cert_pem, key_pem, ca_pem;  // the text it was read from

  TlsMaterial() = default;
  TlsMaterial(const TlsMaterial&) = delete;
  TlsMaterial& operator=(const TlsMaterial&) = delete;
  ~TlsMaterial() {
    X509_free(leaf);
    sk_X509_pop_free(chain, X509_free);
    EVP_PKEY_free(key);
    X509_STORE_free(ca_store);
    sk_X509_NAME_pop_free(ca_names, X509_NAME_free);
  }
};

namespace {

struct BioFree {
  void operator()(BIO* b) const { BIO_free(b); }
};
using Bio = std::unique_ptr<BIO, BioFree>;

Bio MemoryBio(const std::string& pem) { return Bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size()))); }

// Every certificate of `pem`, in order, to `take` (which owns it); how many.
template <typename Take>
int ForEachCertificate(const std::string& pem, Take take) {
  Bio bio = MemoryBio(pem);
  int n = 0;
  while (bio != nullptr) {
    X509* x = PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr);
    if (x == nullptr) break;
    take(x);
    ++n;
  }
  return n;
}

// The certificate's notAfter, Unix s (nullopt when OpenSSL cannot read it as a date).
std::optional<std::int64_t> ExpiryOf(const X509& certificate) {
  const ASN1_TIME* not_after = X509_get0_notAfter(&certificate);
  std::tm utc{};
  if (not_after == nullptr || ASN1_TIME_to_tm(not_after, &utc) != 1) return std::nullopt;
  return static_cast<std::int64_t>(timegm(&utc));
}

// The set in the PEM texts (no client CA when `ca_pem` is empty), or null with *why.
std::shared_ptr<const TlsMaterial> LoadMaterial(const std::string& cert_pem, const std::string& key_pem,
                                                const std::string& ca_pem, std::string* why) {
  auto m = std::make_shared<TlsMaterial>();
  auto fail = [&](const char* what) {
    ERR_clear_error();  // the end of a PEM text reads as an error too
    *why = what;
    return nullptr;
  };
  bool chain_ok = m->chain != nullptr;
  ForEachCertificate(cert_pem, [&](X509* x) {
    if (m->leaf == nullptr) {
      m->leaf = x;
    } else if (!chain_ok || sk_X509_push(m->chain, x) == 0) {
      X509_free(x);
      chain_ok = false;
    }
  });
  if (m->leaf == nullptr || !chain_ok) return fail("the certificate is not valid PEM");
  m->expiry = ExpiryOf(*m->leaf);
  if (Bio bio = MemoryBio(key_pem); bio != nullptr) m->key = PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr);
  if (m->key == nullptr) return fail("the private key is not valid PEM");
  if (X509_check_private_key(m->leaf, m->key) != 1) return fail("the key does not match the certificate");
  if (!ca_pem.empty()) {
    m->ca_store = X509_STORE_new();
    m->ca_names = sk_X509_NAME_new_null();
    bool ca_ok = m->ca_store != nullptr && m->ca_names != nullptr;
    const int cas = ForEachCertificate(ca_pem, [&](X509* x) {
      X509_NAME* name = ca_ok ? X509_NAME_dup(X509_get_subject_name(x)) : nullptr;
      ca_ok = ca_ok && name != nullptr && X509_STORE_add_cert(m->ca_store, x) == 1 &&
              sk_X509_NAME_push(m->ca_names, name) != 0;
      if (!ca_ok) X509_NAME_free(name);
      X509_free(x);
    });
    if (cas == 0 || !ca_ok) return fail("the client CA is not valid PEM");
  }
  ERR_clear_error();
  m->cert_pem = cert_pem;
  m->key_pem = key_pem;
  m->ca_pem = ca_pem;
  return m;
}

// The client CA's names for a handshake to ask for; the handshake owns them.
STACK_OF(X509_NAME)* CaNames(const TlsMaterial& m) { return SSL_dup_CA_list(m.ca_names); }

}  // namespace

bool SetUpTls(SSL_CTX& ctx, const TlsOptions& tls, std::string* why) {
  SSL_CTX_set_min_proto_version(&ctx, TLS1_2_VERSION);
  SSL_CTX_set_options(&ctx, SSL_OP_NO_COMPRESSION | SSL_OP_NO_RENEGOTIATION);
  const auto m = LoadMaterial(tls.cert_chain_pem, tls.private_key_pem, tls.client_ca_pem, why);
  if (m == nullptr) return false;
  bool ok = SSL_CTX_use_certificate(&ctx, m->leaf) == 1 && SSL_CTX_set1_chain(&ctx, m->chain) == 1 &&
            SSL_CTX_use_PrivateKey(&ctx, m->key) == 1;
  if (ok && m->ca_store != nullptr) {
    STACK_OF(X509_NAME)* names = CaNames(*m);
    ok = names != nullptr && SSL_CTX_set1_verify_cert_store(&ctx, m->ca_store) == 1;
    if (names != nullptr) SSL_CTX_set_client_CA_list(&ctx, names);
    SSL_CTX_set_verify(&ctx, SSL_VERIFY_PEER | SSL_VERIFY_FAIL_IF_NO_PEER_CERT, nullptr);
  }
  ERR_clear_error();
  if (!ok) *why = "OpenSSL would not take the certificate";
  return ok;
}

std::string CheckTlsText(const TlsOptions& tls) {
  std::string why;
  return LoadMaterial(tls.cert_chain_pem, tls.private_key_pem, tls.client_ca_pem, &why) != nullptr ? "" : why;
}

std::optional<std::int64_t> CertificateExpiry(const std::string& cert_chain_pem) {
  std::optional<std::int64_t> expiry;
  ForEachCertificate(cert_chain_pem, [&](X509* x) {
    if (!expiry) expiry = ExpiryOf(*x);
    X509_free(x);
  });
  ERR_clear_error();
  return expiry;
}

TlsReloader::TlsReloader(const TlsOptions& tls, std::ostream* log, std::mutex* log_mu)
    : files_{tls.cert_chain_file, tls.private_key_file, tls.client_ca_file},
      interval_(tls.reload_interval),
      log_(log),
      log_mu_(log_mu) {
  for (int i = 0; i < 3; ++i) stamps_[i] = StampOf(files_[i]);
  next_check_ = std::chrono::steady_clock::now() + interval_;
}

TlsReloader::~TlsReloader() = default;

TlsReloader::Stamp TlsReloader::StampOf(const std::string& path) {
  struct stat st {};
  if (path.empty() || stat(path.c_str(), &st) != 0) return {};
  return {static_cast<long long>(st.st_mtim.tv_sec) * 1'000'000'000LL + st.st_mtim.tv_nsec,
          static_cast<long long>(st.st_size)};
}

void TlsReloader::Install(SSL_CTX& ctx) { SSL_CTX_set_cert_cb(&ctx, &TlsReloader::OnCertificate, this); }

int TlsReloader::OnCertificate(SSL* ssl, void* self) {
  const auto m = static_cast<TlsReloader*>(self)->Current();
  if (m == nullptr) return 1;  // the files are as at the start: the context's own set
  bool ok = SSL_use_certificate(ssl, m->leaf) == 1 && SSL_set1_chain(ssl, m->chain) == 1 &&
            SSL_use_PrivateKey(ssl, m->key) == 1;
  if (ok && m->ca_store != nullptr) {
    STACK_OF(X509_NAME)* names = CaNames(*m);
    ok = names != nullptr && SSL_set1_verify_cert_store(ssl, m->ca_store) == 1;
    if (names != nullptr) SSL_set_client_CA_list(ssl, names);
  }
  return ok ? 1 : 0;  // 0 ends the handshake
}

std::optional<std::int64_t> TlsReloader::Expiry(std::optional<std::int64_t> start_expiry) {
  const auto m = Current();
  return m != nullptr ? m->expiry : start_expiry;
}

std::shared_ptr<const TlsMaterial> TlsReloader::Current(bool now) {
  std::lock_guard<std::mutex> lock(mu_);
  const auto t = std::chrono::steady_clock::now();
  if (!now && t < next_check_) return material_;
  next_check_ = t + interval_;
  Stamp stamps[3];
  bool changed = false;
  for (int i = 0; i < 3; ++i) {
    stamps[i] = StampOf(files_[i]);
    changed = changed || !(stamps[i] == stamps_[i]);
  }
  if (!changed) return material_;
  std::string pem[3], why;
  bool read = true;
  for (int i = 0; i < 3 && read; ++i) {
    if (files_[i].empty() || ReadInputFile(files_[i], &pem[i], &why)) continue;
    why = "cannot read '" + files_[i] + "': " + why;
    read = false;
  }
  auto m = read ? LoadMaterial(pem[0], pem[1], pem[2], &why) : nullptr;
  if (m == nullptr) {
    // The stamps stay as they were, so that a set written in several steps is taken
    // once it is whole.
    SayKeptLocked("its files changed but " + why);
    return material_;
  }
  for (int i = 0; i < 3; ++i) stamps_[i] = stamps[i];
  material_ = std::move(m);
  refused_.clear();
  Say("snooker: tls serves the certificate read again from " + files_[0] + "\n");
  return material_;
}

void TlsReloader::SayKept(const std::string& why) {
  std::lock_guard<std::mutex> lock(mu_);
  SayKeptLocked(why);
}

void TlsReloader::SayKeptLocked(const std::string& why) {
  if (why == refused_) return;
  refused_ = why;
  Say("snooker: tls kept the certificate in use; " + why + "\n");
}

void TlsReloader::Say(const std::string& line) {
  if (log_ != nullptr && log_mu_ != nullptr) WriteLogLine(*log_, *log_mu_, [&](std::ostream& out) { out << line; });
}

namespace {

// The text of a set as gRPC reads it: the certificate chain, then its key, in one file
// (OpenSSL's readers of each skip the other's blocks).
std::string IdentityText(const std::string& cert_pem, const std::string& key_pem) {
  std::string text = cert_pem;
  if (!text.empty() && text.back() != '\n') text += '\n';
  return text + key_pem;
}

std::string SystemError(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

}  // namespace

GrpcTlsFiles::GrpcTlsFiles(std::shared_ptr<TlsReloader> reloader) : reloader_(std::move(reloader)) {}

std::unique_ptr<GrpcTlsFiles> GrpcTlsFiles::Start(const TlsOptions& tls, std::shared_ptr<TlsReloader> reloader,
                                                  std::string* why) {
  std::unique_ptr<GrpcTlsFiles> f(new GrpcTlsFiles(std::move(reloader)));
  if (!Replace(IdentityText(tls.cert_chain_pem, tls.private_key_pem), &f->identity_fd_, why)) return nullptr;
  f->identity_path_ = "/proc/self/fd/" + std::to_string(f->identity_fd_);
  if (!tls.client_ca_pem.empty()) {
    if (!Replace(tls.client_ca_pem, &f->ca_fd_, why)) return nullptr;
    f->ca_path_ = "/proc/self/fd/" + std::to_string(f->ca_fd_);
  }
  // gRPC reads them by path: check that the path reaches them.
  std::string text;
  if (!ReadInputFile(f->identity_path_, &text, why)) {
    *why = "cannot read the in-memory certificate file '" + f->identity_path_ + "': " + *why;
    return nullptr;
  }
  if (text != IdentityText(tls.cert_chain_pem, tls.private_key_pem)) {
    *why = "the in-memory certificate file '" + f->identity_path_ + "' does not read back as written";
    return nullptr;
  }
  f->thread_ = std::thread([p = f.get()] { p->Watch(); });
  return f;
}

GrpcTlsFiles::~GrpcTlsFiles() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  for (int fd : {identity_fd_, ca_fd_}) {
    if (fd >= 0) close(fd);
  }
}

bool GrpcTlsFiles::Replace(const std::string& text, int* fd, std::string* why) {
  const int fresh = memfd_create("snooker-tls", MFD_CLOEXEC);
  if (fresh < 0) {
    *why = SystemError("cannot make an in-memory certificate file");
    return false;
  }
  if (std::string reason; !WriteAll(fresh, text, &reason)) {
    *why = "cannot write an in-memory certificate file: " + reason;
    close(fresh);
    return false;
  }
  if (*fd < 0) {
    *fd = fresh;
    return true;
  }
  // dup3 replaces the file behind *fd in one step: a reader opens the old or the new.
  const bool ok = dup3(fresh, *fd, O_CLOEXEC) >= 0;
  if (!ok) *why = SystemError("cannot put an in-memory certificate file in place");
  close(fresh);
  return ok;
}

void GrpcTlsFiles::Watch() {
  std::unique_lock<std::mutex> lock(mu_);
  while (!wake_.wait_for(lock, reloader_->interval(), [&] { return stop_; })) {
    lock.unlock();
    const auto m = reloader_->Current(/*now=*/true);
    if (m != nullptr && m != written_) {
      std::string why;
      // gRPC takes the client CA and the certificate each as it reads them, as it
      // would from the operator's files.
      const bool ok = (m->ca_pem.empty() || Replace(m->ca_pem, &ca_fd_, &why)) &&
                      Replace(IdentityText(m->cert_pem, m->key_pem), &identity_fd_, &why);
      if (ok) {
        written_ = m;
      } else {
        reloader_->SayKept("for gRPC, " + why);  // written_ stays: the next interval tries again
      }
    }
    lock.lock();
  }
}

}  // namespace snooker::server
