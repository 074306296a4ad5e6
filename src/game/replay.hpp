// The player's inputs, stamped with the physics step they apply before, so a
// replay reproduces a round exactly whatever the frame rate was.
//
// File format (text, one item per line, '#' starts a comment):
//   contact2d-replay 1
//   seed 7                       the pass generator's seed
//   dt 1e-05                     the physics step the steps count (must match the pitch)
//   pitch 0123456789abcdef       FNV-1a of the pitch file (a mismatch is a warning)
//   level normal                 easy | normal | hard: the keeper's speed (normal if absent)
//   push 1.6894                  the arrows' force it was recorded with, N (absent: the
//                                pitch's game.push_force, the push before it was derived
//                                from game.push_distance: older replays play as recorded)
//   <step> <key> down|up         e.g. "123000 kick down": applied before step 123000
// Keys: left right up down kick angle_up angle_down reset control power_up
// power_down level_easy level_normal level_hard.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace contact2d::game {

enum class Key {
  Left,
  Right,
  Up,
  Down,
  Kick,
  AngleUp,
  AngleDown,
  Reset,
  Control,
  PowerUp,
  PowerDown,
  LevelEasy,  // the level keys act before the first step and between sessions
  LevelNormal,
  LevelHard
};

std::string_view key_name(Key key);
std::optional<Key> parse_key(std::string_view name);

// The difficulty: how fast the keeper moves (game.keeper_speed_<level>).
enum class Level { Easy, Normal, Hard };
std::string_view level_name(Level level);  // "easy", "normal", "hard"
std::optional<Level> parse_level(std::string_view name);

struct InputEvent {
  long long step = 0;  // applied before the physics step with this index (0 = the first)
  Key key = Key::Kick;
  bool down = true;
};

struct Replay {
  std::uint64_t seed = 0;
  double dt = 0.0;
  std::uint64_t pitch_fingerprint = 0;
  Level level = Level::Normal;
  std::optional<double> push;      // N; nullopt: the pitch's push_force
  std::vector<InputEvent> events;  // non-decreasing steps
};

// Throws InputError naming the file and line.
Replay read_replay(const std::string& path);
Replay parse_replay(const std::string& text, const std::string& origin);

std::string format_replay(const Replay& replay);
// Writes through a temporary file renamed into place. Throws InputError when
// the file cannot be written.
void write_replay(const Replay& replay, const std::string& path);

}  // namespace contact2d::game
