#include "game/session.hpp"

#include "core/format.hpp"
#include "io/json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contact2d::game {

InputFeed::InputFeed(Game& game, const Replay* replay) : game_(game), replay_(replay) {
  // A replay pushes as it was recorded (one without a push line: with the
  // pitch's push_force, the push before it was derived).
  if (replay_) game.use_push(replay_->push.value_or(game.pitch().rules.push_force));
  log_.push = game.push_strength();
  log_.seed = game.seed();
  log_.dt = game.dt();
  log_.pitch_fingerprint = game.pitch().fingerprint;
  log_.level = game.level();
}

void InputFeed::apply_due() {
  if (!replay_) return;
  const auto& events = replay_->events;
  while (next_ < events.size() && events[next_].step <= game_.steps()) {
    const InputEvent& e = events[next_++];
    game_.handle(e.key, e.down);
    log_.events.push_back({game_.steps(), e.key, e.down});
  }
}

void InputFeed::live(Key key, bool down) {
  if (replay_) return;
  game_.handle(key, down);
  log_.events.push_back({game_.steps(), key, down});
}

bool InputFeed::replay_done() const {
  if (!replay_) return true;
  for (size_t i = next_; i < replay_->events.size(); ++i) {
    if (replay_->events[i].down) return false;
  }
  return true;
}

Replay InputFeed::recorded() const { return log_; }

bool session_over(const Game& game, const InputFeed& feed) {
  return game.divergence().has_value() || (game.phase() == Phase::Over && feed.replay_done());
}

void run_headless(Game& game, InputFeed& feed) {
  for (;;) {
    feed.apply_due();
    if (session_over(game, feed)) return;
    game.step();
  }
}

ReplayRun run_replay(const Pitch& pitch, const Replay& replay, const std::string& engine,
                     double sample_dt) {
  Game game(pitch, engine, replay.seed, replay.level);
  InputFeed feed(game, &replay);
  ReplayRun run;
  run.engine = engine;
  const long long stride = std::max(1LL, std::llround(sample_dt / game.dt()));
  for (;;) {
    if (game.steps() % stride == 0) run.samples.push_back({game.time(), game.ball()});
    feed.apply_due();
    if (session_over(game, feed)) break;
    game.step();
  }
  run.json = report_json(game);
  run.outcome = game.current_round().outcome;
  return run;
}

std::optional<double> parting_time(const ReplayRun& a, const ReplayRun& b, double distance) {
  const size_t n = std::min(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = a.samples[i].state.q;
    const Vec3& q = b.samples[i].state.q;
    if (std::hypot(p.x() - q.x(), p.y() - q.y()) > distance) return a.samples[i].t;
  }
  return std::nullopt;
}

namespace {

// Nine digits, null when not finite (io/json.hpp: the one JSON writer).
std::string number(double v) { return json::number(v, 9); }

}  // namespace

std::string report_json(const Game& game) {
  const State& s = game.ball();
  const RoundRecord& last = game.current_round();
  std::string out = "{";
  // "goal" is the last round's outcome, as "outcome" is ("goals" counts them
  // all): the two cannot disagree.
  out += "\"goal\":" + std::string(last.outcome == Outcome::Goal ? "true" : "false");
  out += ",\"goals\":" + std::to_string(game.goals());
  out += ",\"outcome\":" + json::string(std::string(outcome_name(last.outcome)));
  out += ",\"kicks\":[";
  bool first = true;
  for (const KickRecord& k : game.kicks()) {
    out += first ? "" : ",";
    first = false;
    out += "{\"round\":" + std::to_string(k.round) + ",\"step\":" + std::to_string(k.step) +
           ",\"time\":" + number(k.time) + ",\"round_time\":" + number(k.round_time) +
           ",\"distance\":" + number(k.distance) + ",\"angle\":" + number(k.angle) +
           ",\"power\":" + number(k.power) + ",\"counted\":" + (k.counted ? "true" : "false") + "}";
  }
  out += "],\"rounds\":[";
  first = true;
  for (const RoundRecord& r : game.rounds()) {
    out += first ? "" : ",";
    first = false;
    out += "{\"round\":" + std::to_string(r.round) + ",\"pass_speed\":" + number(r.pass_speed) +
           ",\"pass_spin\":" + number(r.pass_spin) + ",\"pass_lift\":" + number(r.pass_lift) +
           ",\"outcome\":" + json::string(std::string(outcome_name(r.outcome))) +
           ",\"end_time\":" + number(r.end_time) + "}";
  }
  out += "],\"time\":" + number(game.time());
  out += ",\"steps\":" + std::to_string(game.steps());
  out += ",\"engine\":" + json::string(std::string(game.engine_name()));
  out += ",\"seed\":" + std::to_string(game.seed());
  out += ",\"level\":" + json::string(std::string(level_name(game.level())));
  out += ",\"session\":" + std::to_string(game.session()) +
         ",\"session_goals\":" + std::to_string(game.session_goals()) +
         ",\"best_session_goals\":" + std::to_string(game.best_session_goals());
  out += ",\"ball\":{\"x\":" + number(s.q.x()) + ",\"y\":" + number(s.q.y()) +
         ",\"vx\":" + number(s.v.x()) + ",\"vy\":" + number(s.v.y()) +
         ",\"omega\":" + number(s.v.z()) + "}";
  out += "}";
  return out;
}

}  // namespace contact2d::game
