// The default impact tables (impact_table.h), compiled in from physics/impact/data/
// (written by tools/impact_tables, see scripts/impact-tables). Without a file the
// library has no such default table, and those impacts go to the solvers.
#include <cstddef>
#include <cstdint>

#include "physics/impact/impact_table.h"

// The bytes of each file between two symbols. The files are build inputs (CMake's
// OBJECT_DEPENDS), so a regenerated table rebuilds this object.
#define SNOOKER_INCBIN(name, file)             \
  asm(".section .rodata\n"                     \
      ".balign 16\n"                           \
      ".global " #name "_begin\n" #name        \
      "_begin:\n"                              \
      ".incbin \"" file "\"\n"                 \
      ".global " #name "_end\n" #name "_end:\n" \
      ".previous\n");                          \
  extern "C" const std::uint8_t name##_begin[]; \
  extern "C" const std::uint8_t name##_end[];

#ifdef SNOOKER_CUSHION_TABLE_FILE
SNOOKER_INCBIN(snooker_cushion_table, SNOOKER_CUSHION_TABLE_FILE)
#endif
#ifdef SNOOKER_BALL_BALL_TABLE_FILE
SNOOKER_INCBIN(snooker_ball_ball_table, SNOOKER_BALL_BALL_TABLE_FILE)
#endif

namespace snooker::physics {
namespace {

// The table of type T held by the bytes [begin, end), read in place once (one
// instance per table type); nullptr if they are unreadable.
template <class T>
const T* Embedded(const std::uint8_t* begin, const std::uint8_t* end) {
  static T table;
  static const bool ok =
      T::Deserialize(begin, static_cast<std::size_t>(end - begin), true, &table).empty();
  return ok ? &table : nullptr;
}

}  // namespace

const CushionTable* DefaultCushionTable() {
#ifdef SNOOKER_CUSHION_TABLE_FILE
  return Embedded<CushionTable>(snooker_cushion_table_begin, snooker_cushion_table_end);
#else
  return nullptr;
#endif
}

const BallBallTable* DefaultBallBallTable() {
#ifdef SNOOKER_BALL_BALL_TABLE_FILE
  return Embedded<BallBallTable>(snooker_ball_ball_table_begin, snooker_ball_ball_table_end);
#else
  return nullptr;
#endif
}

}  // namespace snooker::physics
