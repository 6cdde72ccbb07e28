// Request ids on their own: which ids a client may give a call, and the ids the
// server makes for the others (their form, and that no two of a process meet).
#include "server/request_id.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <thread>
#include <vector>

namespace snooker::server {
namespace {

bool IsNewId(const std::string& id) {
  return id.size() == 16 && id.find_first_not_of("0123456789abcdef") == std::string::npos;
}

TEST(RequestIdTest, PrintableIdsAreKeptAndOthersReplaced) {
  for (const std::string& kept : {std::string("robot-3:shot-412"), std::string("123e4567-e89b-12d3-a456-426614174000"),
                                 std::string("a/b+c=d@e_f.g"), std::string(kMaxRequestIdBytes, 'x')}) {
    EXPECT_TRUE(IsPrintableRequestId(kept)) << kept;
    EXPECT_EQ(RequestIdFor(kept), kept);
  }
  for (const std::string& replaced :
       {std::string(), std::string("two words"), std::string("quote\"d"), std::string("tab\tbed"),
        std::string("new\nline"), std::string("caf\xc3\xa9"), std::string("nul\0l", 5),
        std::string(kMaxRequestIdBytes + 1, 'x')}) {
    EXPECT_FALSE(IsPrintableRequestId(replaced)) << replaced;
    const std::string id = RequestIdFor(replaced);
    EXPECT_NE(id, replaced);
    EXPECT_TRUE(IsNewId(id)) << id;
  }
}

// Made on two threads at once, as the server's connections make them.
TEST(RequestIdTest, NewIdsAreSixteenHexDigitsAndNeverRepeat) {
  constexpr int kEach = 50'000;
  std::vector<std::string> a(kEach), b(kEach);
  std::thread other([&] {
    for (std::string& id : b) id = NewRequestId();
  });
  for (std::string& id : a) id = NewRequestId();
  other.join();
  std::set<std::string> seen;
  for (const auto* ids : {&a, &b}) {
    for (const std::string& id : *ids) {
      ASSERT_TRUE(IsNewId(id)) << id;
      seen.insert(id);
    }
  }
  EXPECT_EQ(seen.size(), 2u * kEach);
}

}  // namespace
}  // namespace snooker::server
