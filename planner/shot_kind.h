// What kind of shot a plan offers, and by which route a pot drops. The planner
// labels every returned shot with both from the shot's own verification run.
#pragma once

#include <cstdint>

namespace snooker::planner {

enum class ShotKind : std::uint8_t {
  kPot,       ///< pots a ball on
  kSafety,    ///< plays a ball on, leaves the opponent as little as it can, drops no ball on
  kEscape,    ///< out of a snooker: a ball on hit first, through cushions; drops no ball on
  kBreakOff,  ///< the frame's first shot, from the D into the reds
  kFoul,      ///< no legal stroke was found: the foul that costs the striker least
};
inline constexpr int kShotKindCount = 5;
/// "POT", "SAFETY", "ESCAPE", "BREAK_OFF", "FOUL" (the API's names).
const char* ToString(ShotKind kind);

enum class PotRoute : std::uint8_t {
  kDirect,  ///< the cue ball hits the potted ball first, neither touches a cushion first
  kPlant,   ///< the cue ball hits a ball on that pots another (a plant, or a set)
  kDouble,  ///< the potted ball reaches the pocket off a cushion
  kKick,    ///< the cue ball reaches the potted ball off a cushion
};
inline constexpr int kPotRouteCount = 4;
/// "DIRECT", "PLANT", "DOUBLE", "KICK" (the API's names).
const char* ToString(PotRoute route);

/// A set of shot kinds or pot routes (a bit per value).
template <typename E, int kCount>
struct EnumSet {
  std::uint8_t bits = static_cast<std::uint8_t>((1u << kCount) - 1);  // all
  static constexpr EnumSet None() { return EnumSet{0}; }
  static constexpr EnumSet Of(E e) { return EnumSet{static_cast<std::uint8_t>(1u << static_cast<int>(e))}; }
  constexpr bool Has(E e) const { return (bits >> static_cast<int>(e)) & 1u; }
  constexpr EnumSet With(E e) const { return EnumSet{static_cast<std::uint8_t>(bits | (1u << static_cast<int>(e)))}; }
  constexpr bool operator==(const EnumSet&) const = default;
};
using ShotKinds = EnumSet<ShotKind, kShotKindCount>;
using PotRoutes = EnumSet<PotRoute, kPotRouteCount>;

}  // namespace snooker::planner
