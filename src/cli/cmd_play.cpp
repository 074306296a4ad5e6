// contact2d play [PITCH.toml] [--engine ref|mujoco] [--seed N] [--level easy|normal|hard]
//                [--record-input FILE] [--replay FILE] [--headless] [--record FILE.mp4]
//                [--frames N] [--no-vsync] [--policy blind|scripted [--seeds N]]
#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <random>

#include "cli/common.hpp"
#include "core/input_error.hpp"
#include "game/game.hpp"
#include "game/pitch.hpp"
#include "game/policy.hpp"
#include "game/session.hpp"
#ifdef CONTACT2D_WITH_WINDOW
#include "game/window.hpp"
#endif

namespace contact2d::cli {
namespace {

// The shortest decimal that reads back as the same double (1e-05, not
// 1.0000000000000001e-05).
std::string shortest(double v) {
  for (int digits = 6; digits < 17; ++digits) {
    std::string text = format_number(v, digits);
    if (std::strtod(text.c_str(), nullptr) == v) return text;
  }
  return format_number(v, 17);
}

std::optional<std::uint64_t> parse_seed(const std::optional<std::string>& given) {
  if (!given) return std::nullopt;
  const std::string& text = *given;
  const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  errno = 0;
  const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
  if (!digits || errno == ERANGE) {
    throw InputError("--seed " + text + ": must be an integer in [0, 18446744073709551615]");
  }
  return v;
}

struct PlayOptions {
  std::string pitch;
  std::string engine = "ref";
  // Checked here, given empty included: CLI11 would wrap "-3" into 2^64 − 3.
  std::optional<std::string> seed;
  std::string record_input;
  std::string replay;
  bool headless = false;
  std::string record;
  long long frames = 0;
  bool no_vsync = false;
  bool help_on_start = false;
  std::optional<std::string> level;   // checked by parse_level
  std::optional<std::string> policy;  // checked by parse_policy
  long long seeds = 0;
  OutputOptions outputs;  // --record-input, --record
};

int play(const PlayOptions& o) {
  using namespace contact2d::game;
  if (o.headless && !o.record.empty())
    throw InputError("--record needs the window: it cannot be used with --headless");
  if (o.headless && o.frames > 0)
    throw InputError("--frames counts window frames: it cannot be used with --headless");
  const std::optional<std::uint64_t> seed_option = parse_seed(o.seed);
  std::optional<Level> level_option;
  if (o.level) {
    level_option = parse_level(*o.level);
    if (!level_option) throw InputError("--level " + *o.level + ": must be easy, normal or hard");
  }
  std::optional<Policy> policy;
  if (o.policy) {
    policy = parse_policy(*o.policy);
    if (!policy) throw InputError("--policy " + *o.policy + ": must be blind or scripted");
    if (!o.headless) throw InputError("--policy plays without a window: it needs --headless");
    if (!o.replay.empty())
      throw InputError("--policy plays its own keys: it cannot be used with --replay");
  }
  if (o.seeds > 0 && !policy)
    throw InputError("--seeds " + std::to_string(o.seeds) +
                     ": counts the rounds a --policy plays; give --policy blind|scripted");
  if (o.seeds > 0 && !o.record_input.empty())
    throw InputError("--record-input records one round: it cannot be used with --seeds");
  o.outputs.check();
  const Pitch pitch = o.pitch.empty() ? default_pitch() : load_pitch(o.pitch);

  std::optional<Replay> replay;
  std::uint64_t seed = 0;
  if (!o.replay.empty()) {
    replay = read_replay(o.replay);
    if (seed_option && *seed_option != replay->seed) {
      throw InputError("--seed " + std::to_string(*seed_option) +
                       " conflicts with the replay's seed " + std::to_string(replay->seed) +
                       " (a replay plays its own passes; drop --seed)");
    }
    if (replay->dt != pitch.scene.sim.dt) {
      throw InputError(o.replay + ": dt " + shortest(replay->dt) +
                       " s does not match the pitch's sim.dt = " + shortest(pitch.scene.sim.dt) +
                       " s (its steps would fall at other times)");
    }
    if (replay->pitch_fingerprint != 0 && replay->pitch_fingerprint != pitch.fingerprint) {
      std::cerr << "contact2d: warning: " << o.replay
                << " was recorded on a different pitch file than " << pitch.path
                << "; the outcome may differ\n";
    }
    seed = replay->seed;
    if (level_option && *level_option != replay->level) {
      throw InputError("--level " + o.level.value_or("") + " conflicts with the replay's level " +
                       std::string(level_name(replay->level)) +
                       " (a replay plays at its own level; drop --level)");
    }
    level_option = replay->level;
  } else {
    seed =
        seed_option
            ? *seed_option
            : (static_cast<std::uint64_t>(std::random_device{}()) << 32 | std::random_device{}());
  }

  const Level level = level_option.value_or(Level::Normal);
  if (policy && o.seeds > 0) {
    // Statistics: one round per seed from --seed (default 1).
    const std::uint64_t first = seed_option.value_or(1);
    const auto runs = run_policy(pitch, o.engine, level, *policy, first, static_cast<int>(o.seeds));
    std::cout << policy_json(runs, *policy, o.engine, level) << "\n";
    return kExitOk;
  }
  Game game(pitch, o.engine, seed, level);
  InputFeed feed(game, replay ? &*replay : nullptr);

  if (policy) {
    play_policy_round(game, feed, *policy);
  } else if (o.headless) {
    run_headless(game, feed);
  } else {
#ifdef CONTACT2D_WITH_WINDOW
    WindowOptions w;
    w.vsync = !o.no_vsync;
    w.record_path = o.record;
    w.max_frames = o.frames;
    w.start_with_help = o.help_on_start;
    const WindowStats stats = run_window(game, feed, w);
    const double fps =
        stats.seconds > 0.0 ? static_cast<double>(stats.frames) / stats.seconds : 0.0;
    const double render_ms =
        stats.frames > 0 ? 1e3 * stats.render_seconds / static_cast<double>(stats.frames) : 0.0;
    std::cerr << "contact2d play: " << stats.frames << " frames in "
              << format_number(stats.seconds, 4) << " s (" << format_number(fps, 4)
              << " fps, drawing " << format_number(render_ms, 3) << " ms/frame), " << stats.steps
              << " physics steps, engine " << o.engine << ", renderer " << stats.renderer << "\n";
#else
    throw InputError(
        "play: the window is not available (contact2d was built without GLFW/OpenGL); use "
        "--headless");
#endif
  }
  if (!o.record_input.empty()) write_replay(feed.recorded(), o.record_input);
  std::cout << report_json(game) << "\n";
  if (game.divergence()) {
    std::cerr << "contact2d: " << pitch.path << ": " << describe(*game.divergence(), pitch.scene)
              << "\n";
    return kExitDiverged;
  }
  return kExitOk;
}

}  // namespace

Command add_play(CLI::App& app) {
  auto o = std::make_shared<PlayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "play",
      "The game: receive the teammate's pass, control it, beat the keeper: kick it (K) into the "
      "goal from at least 1 m.\n"
      "Keys: C controls (brakes) the ball, arrows push it, W/S change the kick angle, A/D its "
      "power, K or Enter kicks,\n"
      "Space pauses, Backspace resets to the next pass, F1 or H shows the help, Esc quits. Prints "
      "one JSON line at the end.");
  cmd->add_option(
         "pitch", o->pitch,
         "Pitch file: any circle scene; its [game] table names the crossbar and the rules, without "
         "one it plays on the built-in goal (default: the built-in pitch)")
      ->type_name("PITCH.toml");
  add_engine_kind_option(*cmd, o->engine,
                         ": the physics (same keys, replays and recording on both)");
  cmd->add_option("--seed", o->seed,
                  "Seed of the passes (default: random; the JSON and the replay say which)")
      ->type_name("N");
  o->outputs.file(*cmd, "--record-input", o->record_input,
                  "Save the key events (stamped with physics steps) to this replay file", "FILE");
  cmd->add_option("--replay", o->replay,
                  "Play back a replay file (its seed, its inputs; live keys are ignored)")
      ->type_name("FILE");
  o->outputs.input("pitch file", o->pitch);
  o->outputs.input("replay file", o->replay);
  cmd->add_flag("--headless", o->headless,
                "No window: run as fast as possible and print the JSON line");
  o->outputs.file(*cmd, "--record", o->record,
                  "Write a video of the window to this .mp4 file (through ffmpeg)", "FILE.mp4");
  cmd->add_option("--frames", o->frames,
                  "Close the window after this many frames (to measure the frame rate)")
      ->type_name("N")
      ->check(CLI::Range(1LL, 100000000LL));
  cmd->add_flag("--no-vsync", o->no_vsync,
                "Do not wait for the display's refresh (to measure the frame rate)");
  cmd->add_flag("--help-overlay", o->help_on_start, "Start with the help overlay shown");
  cmd->add_option("--level", o->level,
                  "Difficulty: how fast the keeper moves, easy, normal or hard (default normal; "
                  "a replay plays at its own)")
      ->type_name("LEVEL");
  cmd->add_option("--policy", o->policy,
                  "With --headless: a built-in player plays the round, blind (one kick at 0.1 s) "
                  "or scripted (controls, dribbles to " +
                      format_number("%g", game::kScriptedDribbleTo) +
                      " m from the goal line, chips the keeper)")
      ->type_name("NAME");
  cmd->add_option("--seeds", o->seeds,
                  "With --policy: play one round on each of N seeds from --seed (default 1) and "
                  "print the goals and outcomes as one JSON line")
      ->type_name("N")
      ->check(CLI::Range(1LL, 1000000LL));
  return {cmd, [o] { return play(*o); }};
}

}  // namespace contact2d::cli
