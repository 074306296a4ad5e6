// Running a game from a stream of inputs: live keys (recorded) or a replay,
// applied between physics steps at their step index; the end condition
// shared by the headless runner and the window; the one-line JSON report.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/run.hpp"

#include "game/game.hpp"
#include "game/replay.hpp"

namespace contact2d::game {

class InputFeed {
 public:
  // replay: events to play back (live input is then ignored); may be null.
  InputFeed(Game& game, const Replay* replay);

  // Applies the replay's events due before the next step.
  void apply_due();
  // A live key: applied now and recorded at the current step (ignored while
  // a replay plays).
  void live(Key key, bool down);

  bool replaying() const { return replay_ != nullptr; }
  // No key press left to play back (releases cannot start anything).
  bool replay_done() const;
  // The inputs as a replay file (live ones, or the replay's own).
  Replay recorded() const;

 private:
  Game& game_;
  const Replay* replay_;
  size_t next_ = 0;
  Replay log_;
};

// The session is over: the current round has ended and no key press is left
// to play back. With no replay, one round.
bool session_over(const Game& game, const InputFeed& feed);

// Steps the game until session_over (or divergence), as fast as it can.
void run_headless(Game& game, InputFeed& feed);

// A replay played headless on one engine, with the ball sampled along the
// way: what the report shows for both engines.
struct ReplayRun {
  std::string engine;
  std::string json;                 // report_json at the end
  Outcome outcome = Outcome::None;  // of the last round
  std::vector<Sample> samples;      // session time and ball state every sample_dt
};
// Throws InputError when the engine cannot run the pitch.
ReplayRun run_replay(const Pitch& pitch, const Replay& replay, const std::string& engine,
                     double sample_dt = 1e-3);

// Where two runs of the same replay part: the first sample time at which
// the ball centres are more than `distance` apart; nullopt when they never
// are (over the samples both have).
std::optional<double> parting_time(const ReplayRun& a, const ReplayRun& b, double distance);

// One JSON line (no newline): goal, goals, outcome, rounds, kicks, time,
// steps, engine, seed, ball.
std::string report_json(const Game& game);

}  // namespace contact2d::game
