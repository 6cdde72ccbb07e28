# Writes OUTPUT, a C++ source that defines snooker::server::WebFiles()
# (server/web_files.h): every regular file directly in SOURCE_DIR (not in its
# folders; none whose name starts with a dot), each as a string literal of its
# bytes, with a content type chosen by its extension. Run as a build step
# (server/CMakeLists.txt): cmake -DSOURCE_DIR=... -DOUTPUT=... -P embed_files.cmake
cmake_minimum_required(VERSION 3.25)

function(content_type name out)
  string(REGEX MATCH "\\.[^.]*$" ext "${name}")
  string(TOLOWER "${ext}" ext)
  if(ext MATCHES "^\\.html?$")
    set(type "text/html; charset=utf-8")
  elseif(ext MATCHES "^\\.m?js$")
    set(type "text/javascript; charset=utf-8")
  elseif(ext STREQUAL ".css")
    set(type "text/css; charset=utf-8")
  elseif(ext STREQUAL ".txt")
    set(type "text/plain; charset=utf-8")
  elseif(ext MATCHES "^\\.(json|map)$")
    set(type "application/json")
  elseif(ext STREQUAL ".svg")
    set(type "image/svg+xml")
  elseif(ext STREQUAL ".png")
    set(type "image/png")
  elseif(ext MATCHES "^\\.jpe?g$")
    set(type "image/jpeg")
  elseif(ext STREQUAL ".ico")
    set(type "image/x-icon")
  elseif(ext STREQUAL ".woff2")
    set(type "font/woff2")
  elseif(ext STREQUAL ".wasm")
    set(type "application/wasm")
  else()
    set(type "application/octet-stream")
  endif()
  set(${out} "${type}" PARENT_SCOPE)
endfunction()

file(GLOB paths LIST_DIRECTORIES false "${SOURCE_DIR}/*")
list(SORT paths)
set(arrays "")
set(entries "")
set(index 0)
foreach(path IN LISTS paths)
  get_filename_component(name "${path}" NAME)
  if(name MATCHES "^\\.")
    continue()
  endif()
  if(NOT name MATCHES "^[A-Za-z0-9._-]+$")
    message(FATAL_ERROR "web/${name}: a served file's name may have only letters, digits, '.', '_' and '-'")
  endif()
  content_type("${name}" type)
  file(READ "${path}" hex HEX)
  string(LENGTH "${hex}" hex_length)
  math(EXPR size "${hex_length} / 2")
  # Every byte as \xHH, 32 bytes to a line.
  set(literal "")
  set(at 0)
  while(at LESS hex_length)
    string(SUBSTRING "${hex}" ${at} 64 chunk)
    string(REGEX REPLACE "([0-9a-f][0-9a-f])" "\\\\x\\1" chunk "${chunk}")
    string(APPEND literal "\n    \"${chunk}\"")
    math(EXPR at "${at} + 64")
  endwhile()
  if(size EQUAL 0)
    set(literal " \"\"")
  endif()
  string(APPEND arrays "// web/${name}, ${size} bytes\nconstexpr char kFile${index}[] =${literal};\n\n")
  string(APPEND entries "      {\"${name}\", \"${type}\", std::string_view(kFile${index}, ${size})},\n")
  math(EXPR index "${index} + 1")
endforeach()

if(index EQUAL 0)
  set(body "  return {};\n")
else()
  set(body "  static constexpr WebFile kFiles[] = {\n${entries}  };\n  return kFiles;\n")
endif()
file(WRITE "${OUTPUT}.tmp" "// Generated from web/ by server/embed_files.cmake at build time: do not edit.
#include \"server/web_files.h\"

namespace snooker::server {
namespace {

${arrays}}  // namespace

std::span<const WebFile> WebFiles() {
${body}}

}  // namespace snooker::server
")
# Replaced only when it changes, so that an unchanged page does not recompile.
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
