#include "cli/args.h"

#include <charconv>
#include <cmath>

namespace snooker::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& switches) {
  for (size_t i = 0; i < argv.size() && error_.empty(); ++i) {
    const std::string& a = argv[i];
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      Fail("unexpected argument '" + a + "'");
      break;
    }
    std::string name = a.substr(2);
    std::optional<std::string> inline_value;
    if (const size_t eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (switches.count(name) > 0) {
      if (inline_value) {
        Fail("--" + name + " takes no value (got '" + *inline_value + "')");
      } else {
        switches_on_.insert(name);
      }
    } else if (valued.count(name) > 0) {
      if (inline_value) {
        values_[name] = *inline_value;
      } else if (i + 1 < argv.size()) {
        values_[name] = argv[++i];
      } else {
        Fail("--" + name + " needs a value");
      }
      // An empty path or address (an unset shell variable) would otherwise read as
      // the flag left out: no picture, no log, no HTTP, and exit 0.
      if (values_.count(name) > 0 && values_[name].empty()) {
        Fail("--" + name + " needs a value; it was given an empty one");
      }
    } else {
      Fail("unknown option --" + name);
    }
  }
}

namespace {

// All of `t` read as a T (std::from_chars: no sign for an unsigned T, no leading space).
template <class T>
bool ParseAll(const std::string& t, T* x) {
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), *x);
  return ec == std::errc() && end == t.data() + t.size() && !t.empty();
}

// True when `t` is a whole number too large for a long: digits, perhaps after a '-',
// that from_chars reads to the end but cannot hold.
bool WholeButTooLarge(const std::string& t) {
  long x = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  return ec == std::errc::result_out_of_range && end == t.data() + t.size();
}

}  // namespace

const std::string* Args::Find(const std::string& name, bool has_fallback) {
  const auto it = values_.find(name);
  if (it != values_.end()) return &it->second;
  if (!has_fallback) Fail("--" + name + " is required");
  return nullptr;
}

std::optional<double> Args::Number(const std::string& name, std::optional<double> fallback) {
  const std::string* t = Find(name, fallback.has_value());
  if (!t) return fallback;
  double x = 0;
  if (!ParseAll(*t, &x)) {
    Fail("--" + name + " '" + *t + "' is not a number");
    return std::nullopt;
  }
  if (!std::isfinite(x)) {
    Fail("--" + name + " '" + *t + "' is not a finite number");
    return std::nullopt;
  }
  return x;
}

std::optional<long> Args::Integer(const std::string& name, std::optional<long> fallback, long lo,
                                  long hi) {
  const std::string* t = Find(name, fallback.has_value());
  if (!t) return fallback;
  long x = 0;
  const bool whole = ParseAll(*t, &x);
  if (!whole && !WholeButTooLarge(*t)) {
    Fail("--" + name + " '" + *t + "' is not a whole number");
    return std::nullopt;
  }
  if (!whole || x < lo || x > hi) {
    Fail("--" + name + " " + *t + " is out of range [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
    return std::nullopt;
  }
  return x;
}

std::optional<std::uint64_t> Args::Unsigned64(const std::string& name, std::optional<std::uint64_t> fallback) {
  const std::string* t = Find(name, fallback.has_value());
  if (!t) return fallback;
  std::uint64_t x = 0;
  if (!ParseAll(*t, &x)) {
    Fail("--" + name + " '" + *t + "' is not a whole number in [0, 18446744073709551615]");
    return std::nullopt;
  }
  return x;
}

std::optional<std::string> Args::Text(const std::string& name,
                                      std::optional<std::string> fallback) {
  const std::string* t = Find(name, fallback.has_value());
  if (!t) return fallback;
  return *t;
}

}  // namespace snooker::cli
