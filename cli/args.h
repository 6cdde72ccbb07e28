// A small strict command-line flag parser: --name value, --name=value and boolean
// switches. Every error names the flag and the offending text.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace snooker::cli {

class Args {
 public:
  /// `valued`: flags that take a value; `switches`: flags that do not. Names are
  /// given without the leading "--". Unknown flags, stray words and empty values are
  /// errors.
  Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
       const std::set<std::string>& switches);

  /// Empty when parsing succeeded; otherwise the first error.
  const std::string& error() const { return error_; }

  bool Has(const std::string& name) const { return values_.count(name) > 0; }
  bool Switch(const std::string& name) const { return switches_on_.count(name) > 0; }

  /// A finite double; unset -> `fallback`. On a bad value sets error() and returns nullopt.
  std::optional<double> Number(const std::string& name, std::optional<double> fallback);
  /// An integer within [lo, hi]; unset -> `fallback`.
  std::optional<long> Integer(const std::string& name, std::optional<long> fallback, long lo,
                              long hi);
  /// A whole number in [0, 2^64 - 1] (a seed: the API's uint64); unset -> `fallback`.
  std::optional<std::uint64_t> Unsigned64(const std::string& name, std::optional<std::uint64_t> fallback);
  /// Raw text; unset -> `fallback`.
  std::optional<std::string> Text(const std::string& name, std::optional<std::string> fallback);

 private:
  /// The value given for `name`; nullptr when unset, and then, without a fallback,
  /// error() says it is required.
  const std::string* Find(const std::string& name, bool has_fallback);
  void Fail(std::string message) {  // keeps the first error
    if (error_.empty()) error_ = std::move(message);
  }
  std::map<std::string, std::string> values_;
  std::set<std::string> switches_on_;
  std::string error_;
};

}  // namespace snooker::cli
