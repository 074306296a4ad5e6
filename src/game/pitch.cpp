#include "game/pitch.hpp"

#include "core/format.hpp"

#include <toml++/toml.h>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/rng.hpp"
#include "io/read_file.hpp"
#include "io/scene_file.hpp"
#include "io/toml_table.hpp"

namespace contact2d::game {

extern const char* const kDefaultPitchToml;  // generated from validation/scenes/game/pitch.toml

namespace {

constexpr const char* kBuiltInOrigin = "the built-in pitch (validation/scenes/game/pitch.toml)";

std::string format_value(double v) { return format_number("%g", v); }

// Reads the [game] table: numbers only, every key checked against its range
// as it is read, unknown keys rejected (io's TableReader does the typing).
class GameTable {
 public:
  GameTable(const toml::table* table, std::string origin)
      : reader_(table, "game.", origin), origin_(std::move(origin)) {}

  void number(const char* key, double& out, double lo, double hi, const char* range) {
    reader_.number(key, out);
    check(key, out, std::isfinite(out) && out >= lo && out <= hi, range);
  }

  void integer(const char* key, int& out, int lo, int hi, const char* range) {
    long long v = out;
    reader_.integer(key, v);
    check(key, static_cast<double>(v), v >= lo && v <= hi, range);
    out = static_cast<int>(v);
  }

  void check(const std::string& key, double value, bool ok, const std::string& range) const {
    if (!ok) {
      throw InputError(origin_ + ": game." + key + " = " + format_value(value) +
                       " is out of range: " + range);
    }
  }

  void reject_unknown() const { reader_.reject_unknown(); }

 private:
  TableReader reader_;
  std::string origin_;
};

Rules read_rules(const toml::table* table, const Scene& scene, const std::string& origin) {
  Rules r;
  GameTable g(table, origin);
  constexpr double kBig = 1e6;
  g.number("goal_line", r.goal_line, -kBig, kBig, "must be finite, |goal_line| <= 1e6 m");
  g.integer("crossbar", r.crossbar, 0, 1'000'000,
            "must be the index of a box in [[obstacle]], counted from 0");
  g.integer("keeper", r.keeper, -1, 1'000'000,
            "must be -1 (no keeper) or the index of a box in [[obstacle]], counted from 0");
  g.number("keeper_speed_easy", r.keeper_speed_easy, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("keeper_speed_normal", r.keeper_speed_normal, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("keeper_speed_hard", r.keeper_speed_hard, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("reach_height", r.reach_height, 0.0, 100.0, "must be in [0, 100] m");
  g.number("control_force", r.control_force, 0.0, 1e4, "must be in [0, 1e4] N");
  g.number("control_time", r.control_time, 1e-4, 100.0, "must be in [1e-4, 100] s");
  g.number("min_kick_distance", r.min_kick_distance, 0.0, 1e3, "must be in [0, 1e3] m");
  g.number("kick_impulse", r.kick_impulse, 0.0, 1e4, "must be in [0, 1e4] N·s");
  g.number("kick_duration", r.kick_duration, 1e-6, 10.0, "must be in [1e-6, 10] s");
  g.number("kick_angle_min", r.kick_angle_min, -90.0, 90.0, "must be in [-90, 90] degrees");
  g.number("kick_angle_max", r.kick_angle_max, -90.0, 90.0, "must be in [-90, 90] degrees");
  g.number("kick_angle", r.kick_angle, -90.0, 90.0, "must be in [-90, 90] degrees");
  g.number("kick_angle_step", r.kick_angle_step, 1e-3, 90.0, "must be in [1e-3, 90] degrees");
  g.number("kick_power_min", r.kick_power_min, 0.01, 1.0, "must be in [0.01, 1]");
  g.number("kick_power", r.kick_power, 0.01, 1.0, "must be in [0.01, 1]");
  g.number("kick_power_step", r.kick_power_step, 1e-3, 1.0, "must be in [1e-3, 1]");
  g.number("push_force", r.push_force, 0.0, 1e4, "must be in [0, 1e4] N");
  g.number("push_distance", r.push_distance, 0.0, 1e3, "must be in [0, 1e3] m");
  g.number("push_time", r.push_time, 1e-3, 100.0, "must be in [1e-3, 100] s");
  g.number("pass_x", r.pass_x, -kBig, kBig, "must be finite, |pass_x| <= 1e6 m");
  g.number("pass_speed_min", r.pass_speed_min, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("pass_speed_max", r.pass_speed_max, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("pass_spin_min", r.pass_spin_min, -10.0, 10.0,
           "must be in [-10, 10] (multiples of rolling spin)");
  g.number("pass_spin_max", r.pass_spin_max, -10.0, 10.0,
           "must be in [-10, 10] (multiples of rolling spin)");
  g.number("pass_lift_min", r.pass_lift_min, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("pass_lift_max", r.pass_lift_max, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("round_time", r.round_time, 1e-3, 1e4, "must be in [1e-3, 1e4] s");
  g.number("rest_speed", r.rest_speed, 0.0, 100.0, "must be in [0, 100] m/s");
  g.number("rest_time", r.rest_time, 0.0, 1e3, "must be in [0, 1e3] s");
  g.number("result_time", r.result_time, 0.0, 1e3, "must be in [0, 1e3] s");
  g.integer("session_rounds", r.session_rounds, 1, 1'000'000, "must be in [1, 1000000] passes");
  g.number("pitch_min_x", r.pitch_min_x, -kBig, kBig, "must be finite, |pitch_min_x| <= 1e6 m");
  g.number("pitch_max_x", r.pitch_max_x, -kBig, kBig, "must be finite, |pitch_max_x| <= 1e6 m");
  g.reject_unknown();

  // Relations between keys.
  g.check("kick_angle_max", r.kick_angle_max, r.kick_angle_max >= r.kick_angle_min,
          "must be >= game.kick_angle_min = " + format_value(r.kick_angle_min));
  g.check("kick_angle", r.kick_angle,
          r.kick_angle >= r.kick_angle_min && r.kick_angle <= r.kick_angle_max,
          "must be in [game.kick_angle_min, game.kick_angle_max] = [" +
              format_value(r.kick_angle_min) + ", " + format_value(r.kick_angle_max) + "] degrees");
  g.check("pass_speed_max", r.pass_speed_max, r.pass_speed_max >= r.pass_speed_min,
          "must be >= game.pass_speed_min = " + format_value(r.pass_speed_min) + " m/s");
  g.check("pass_spin_max", r.pass_spin_max, r.pass_spin_max >= r.pass_spin_min,
          "must be >= game.pass_spin_min = " + format_value(r.pass_spin_min));
  g.check("pass_lift_max", r.pass_lift_max, r.pass_lift_max >= r.pass_lift_min,
          "must be >= game.pass_lift_min = " + format_value(r.pass_lift_min) + " m/s");
  g.check("kick_power", r.kick_power, r.kick_power >= r.kick_power_min,
          "must be in [game.kick_power_min, 1] = [" + format_value(r.kick_power_min) + ", 1]");
  g.check("pitch_max_x", r.pitch_max_x, r.pitch_max_x > r.pitch_min_x,
          "must be > game.pitch_min_x = " + format_value(r.pitch_min_x) + " m");
  g.check("pass_x", r.pass_x, r.pass_x > r.pitch_min_x && r.pass_x < r.pitch_max_x,
          "must be inside (game.pitch_min_x, game.pitch_max_x) = (" + format_value(r.pitch_min_x) +
              ", " + format_value(r.pitch_max_x) + ") m");
  g.check("goal_line", r.goal_line, r.goal_line != r.pass_x,
          "must differ from game.pass_x (the goal is on one side)");
  const int boxes = static_cast<int>(scene.obstacles.size());
  if (boxes == 0 && table && !table->contains("crossbar")) {
    throw InputError(origin +
                     ": [game] needs a crossbar, a box in [[obstacle]] named by game.crossbar "
                     "(the scene has no obstacles); leave [game] out to play on the built-in goal");
  }
  g.check("crossbar", r.crossbar,
          r.crossbar < boxes &&
              scene.obstacles[static_cast<size_t>(r.crossbar)].shape == ObstacleShape::Box,
          "must be the index of a box in [[obstacle]] (the scene has " + std::to_string(boxes) +
              " obstacles, counted from 0)");
  if (r.keeper >= 0) {
    const auto k = static_cast<size_t>(r.keeper);
    g.check("keeper", r.keeper,
            r.keeper < boxes && r.keeper != r.crossbar &&
                scene.obstacles[k].shape == ObstacleShape::Box,
            "must be -1 (no keeper) or the index of a box in [[obstacle]] other than the crossbar "
            "(the scene has " +
                std::to_string(boxes) + " obstacles, counted from 0)");
    const Obstacle& bar = scene.obstacles[static_cast<size_t>(r.crossbar)];
    g.check("keeper", r.keeper, scene.obstacles[k].b.y() < bar.a.y(),
            "must be a box whose top is below the crossbar's underside (" +
                format_value(bar.a.y()) + " m): it moves up to it");
  }
  return r;
}

}  // namespace

double Pitch::crossbar_bottom() const {
  return scene.obstacles.at(static_cast<size_t>(rules.crossbar)).a.y();
}

double Pitch::keeper_speed(Level level) const {
  switch (level) {
    case Level::Easy: return rules.keeper_speed_easy;
    case Level::Normal: return rules.keeper_speed_normal;
    case Level::Hard: return rules.keeper_speed_hard;
  }
  return rules.keeper_speed_normal;
}

Pitch parse_pitch(const std::string& toml_text, const std::string& origin) {
  Pitch pitch;
  pitch.scene = parse_scene(
      toml_text, origin);  // the physics, [[obstacle]] included; checks [game] is a table
  if (!shape_features(pitch.scene.shape).rolls) {  // the ball
    throw InputError(origin + ": scene = \"" + std::string(shape_name(pitch.scene.shape)) +
                     "\" cannot be played: the game needs scene = \"circle\" (the ball)");
  }
  const toml::table root = toml::parse(toml_text, origin);  // parsed fine above
  const toml::table* game = root["game"].as_table();
  if (!game && origin != kBuiltInOrigin) {
    // Any circle scene plays: without [game] it gets the built-in pitch's
    // goal (its obstacles first, so that game.crossbar = 0 is its crossbar,
    // then the scene's own) and rules. The goal's obstacles keep the laws
    // they set (the net's) and take the scene's [contact] for the rest.
    const Pitch built_in = default_pitch();
    std::vector<Obstacle> obstacles = built_in.scene.obstacles;
    obstacles.insert(obstacles.end(), pitch.scene.obstacles.begin(), pitch.scene.obstacles.end());
    pitch.scene.obstacles = std::move(obstacles);
    pitch.rules = built_in.rules;
    pitch.goal_from_built_in = true;
  } else {
    pitch.rules = read_rules(game, pitch.scene, origin);
  }
  if (pitch.rules.keeper >= 0)
    pitch.scene.obstacles[static_cast<size_t>(pitch.rules.keeper)].moves = true;
  pitch.path = origin;
  pitch.fingerprint = fnv1a(toml_text);
  return pitch;
}

Pitch load_pitch(const std::string& path) {
  return parse_pitch(read_input_file(path, "pitch file"), path);
}

Pitch default_pitch() { return parse_pitch(kDefaultPitchToml, kBuiltInOrigin); }

}  // namespace contact2d::game
