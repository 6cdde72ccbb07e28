// The files of the top-level web/ folder (the browser page), built into the binary:
// server/embed_files.cmake writes each one into a generated source as bytes with
// its content type, so the HTTP server (http_server.h) reads nothing from disk.
#pragma once

#include <span>
#include <string_view>

namespace snooker::server {

struct WebFile {
  std::string_view name;          ///< "index.html": the file's name in web/
  std::string_view content_type;  ///< "text/html; charset=utf-8", by the name's extension
  std::string_view bytes;
};

/// Every file of web/ when the binary was built, in name order.
std::span<const WebFile> WebFiles();

/// The file of that name, or null.
inline const WebFile* FindWebFile(std::string_view name) {
  for (const WebFile& f : WebFiles()) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

}  // namespace snooker::server
