#include "game/replay.hpp"

#include "core/format.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"

namespace contact2d::game {
namespace {

constexpr Key kKeys[] = {Key::Left,        Key::Right,    Key::Up,        Key::Down,
                         Key::Kick,        Key::AngleUp,  Key::AngleDown, Key::Reset,
                         Key::Control,     Key::PowerUp,  Key::PowerDown, Key::LevelEasy,
                         Key::LevelNormal, Key::LevelHard};
constexpr const char* kAllowedKeys =
    "left, right, up, down, kick, angle_up, angle_down, reset, control, power_up, power_down, "
    "level_easy, level_normal, level_hard";
constexpr Level kLevels[] = {Level::Easy, Level::Normal, Level::Hard};

bool parse_u64(const std::string& text, std::uint64_t& out, int base) {
  if (text.empty() || text[0] == '-' || text[0] == '+') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, base);
  if (errno != 0 || *end != '\0') return false;
  out = v;
  return true;
}

}  // namespace

std::string_view key_name(Key key) {
  switch (key) {
    case Key::Left: return "left";
    case Key::Right: return "right";
    case Key::Up: return "up";
    case Key::Down: return "down";
    case Key::Kick: return "kick";
    case Key::AngleUp: return "angle_up";
    case Key::AngleDown: return "angle_down";
    case Key::Reset: return "reset";
    case Key::Control: return "control";
    case Key::PowerUp: return "power_up";
    case Key::PowerDown: return "power_down";
    case Key::LevelEasy: return "level_easy";
    case Key::LevelNormal: return "level_normal";
    case Key::LevelHard: return "level_hard";
  }
  return "?";
}

std::string_view level_name(Level level) {
  switch (level) {
    case Level::Easy: return "easy";
    case Level::Normal: return "normal";
    case Level::Hard: return "hard";
  }
  return "?";
}

std::optional<Level> parse_level(std::string_view name) {
  for (Level level : kLevels) {
    if (level_name(level) == name) return level;
  }
  return std::nullopt;
}

std::optional<Key> parse_key(std::string_view name) {
  for (Key key : kKeys) {
    if (key_name(key) == name) return key;
  }
  return std::nullopt;
}

Replay parse_replay(const std::string& text, const std::string& origin) {
  Replay replay;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  bool header = false, have_seed = false, have_dt = false;
  auto fail = [&](const std::string& why) -> void {
    throw InputError(origin + ":" + std::to_string(number) + ": " + why);
  };
  while (std::getline(in, line)) {
    ++number;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string first;
    if (!(words >> first)) continue;
    std::string second, third, extra;
    words >> second >> third >> extra;
    if (!extra.empty()) fail("unexpected '" + extra + "' at the end of the line");
    if (!header) {
      if (first != "contact2d-replay" || second != "1" || !third.empty()) {
        fail("not a replay file: the first line must be 'contact2d-replay 1'");
      }
      header = true;
      continue;
    }
    if (first == "seed") {
      if (!parse_u64(second, replay.seed, 10) || !third.empty())
        fail("seed must be an integer in [0, 2^64)");
      have_seed = true;
    } else if (first == "dt") {
      char* end = nullptr;
      replay.dt = std::strtod(second.c_str(), &end);
      if (second.empty() || *end != '\0' || !std::isfinite(replay.dt) || replay.dt <= 0.0 ||
          !third.empty()) {
        fail("dt must be a number > 0 (the physics step, s)");
      }
      have_dt = true;
    } else if (first == "pitch") {
      if (second.size() != 16 || !parse_u64(second, replay.pitch_fingerprint, 16) ||
          !third.empty()) {
        fail("pitch must be 16 hexadecimal digits (the pitch file's FNV-1a)");
      }
    } else if (first == "push") {
      char* end = nullptr;
      const double push = std::strtod(second.c_str(), &end);
      if (second.empty() || *end != '\0' || !std::isfinite(push) || push < 0.0 || push > 1e4 ||
          !third.empty()) {
        fail("push must be a number in [0, 1e4] (the arrows' force, N)");
      }
      replay.push = push;
    } else if (first == "level") {
      const auto level = parse_level(second);
      if (!level || !third.empty()) fail("level must be easy, normal or hard");
      replay.level = *level;
    } else {
      std::uint64_t step = 0;
      if (!parse_u64(first, step, 10) || step > (1ull << 62)) {
        fail(
            "'" + first +
            "' is not a step index, seed, dt, pitch, level or push line (event lines: <step> <key> "
            "down|up)");
      }
      const auto key = parse_key(second);
      if (!key) fail("key '" + second + "' is not one of " + kAllowedKeys);
      if (third != "down" && third != "up")
        fail("key action '" + third + "' must be 'down' or 'up'");
      const long long s = static_cast<long long>(step);
      if (!replay.events.empty() && s < replay.events.back().step) {
        fail("step " + first + " is earlier than the line before (events must be in step order)");
      }
      replay.events.push_back({s, *key, third == "down"});
    }
  }
  if (!header)
    throw InputError(origin + ": empty file: not a replay (first line 'contact2d-replay 1')");
  if (!have_seed) throw InputError(origin + ": missing 'seed' line");
  if (!have_dt) throw InputError(origin + ": missing 'dt' line");
  return replay;
}

Replay read_replay(const std::string& path) {
  // One line per key change: a goal's is about 1 kB, far below the cap.
  return parse_replay(read_input_file(path, "replay file"), path);
}

std::string format_replay(const Replay& replay) {
  std::ostringstream out;
  const std::string fingerprint =
      format_text("%016llx", static_cast<unsigned long long>(replay.pitch_fingerprint));
  // The shortest decimal that reads back as the same double.
  const std::string dt = format_shortest(replay.dt, 6);
  out << "contact2d-replay 1\n"
      << "# inputs of contact2d play, stamped with the physics step they apply before\n"
      << "seed " << replay.seed << "\n"
      << "dt " << dt << "\n"
      << "pitch " << fingerprint << "\n"
      << "level " << level_name(replay.level) << "\n";
  if (replay.push) out << "push " << format_shortest(*replay.push, 6) << "\n";
  for (const InputEvent& e : replay.events) {
    out << e.step << " " << key_name(e.key) << " " << (e.down ? "down" : "up") << "\n";
  }
  return out.str();
}

void write_replay(const Replay& replay, const std::string& path) {
  AtomicFile out(path);
  const std::string text = format_replay(replay);
  if (std::fwrite(text.data(), 1, text.size(), out.get()) != text.size()) {
    throw InputError(path + ": cannot write replay file (write error)");
  }
  out.commit();
}

}  // namespace contact2d::game
