#include <sstream>

#include "analysis/real_trajectories.hpp"
#include "core/format.hpp"
#include "io/json.hpp"

namespace contact2d::analysis {

namespace {

constexpr const char* kMetric =
    "largest over the samples of the window of the RMS distance (m) between the body's four "
    "reference points (a box's corners) predicted and recorded, matched up to the outline's "
    "symmetry";

std::string quartiles_json(const Quartiles& q) {
  return "{\"median\": " + json::number(q.median) + ", \"iqr\": " + json::number(q.q3 - q.q1) +
         ", \"q1\": " + json::number(q.q1) + ", \"q3\": " + json::number(q.q3) + "}";
}

}  // namespace

std::string trajectory_fit_json(const TrajectoryFit& fit) {
  std::ostringstream o;
  o << "{\"recording\": " << json::string(fit.recording) << ", \"kind\": \"trajectories\""
    << ", \"peer\": " << json::string(fit.peer) << ", \"trajectories\": " << fit.trajectories
    << ", \"samples\": " << fit.samples << ", \"window_s\": " << json::number(fit.window)
    << ", \"omega_dt\": " << json::number(fit.omega_dt) << ", \"lifted_to_touch\": " << fit.lifted
    << ", \"median_lift_m\": " << json::number(fit.median_lift)
    << ", \"mass\": " << json::number(fit.mass) << ", \"inertia\": " << json::number(fit.inertia)
    << ", \"metric\": " << json::string(kMetric)
    << ", \"seconds\": " << json::number(fit.seconds, 4) << ", \"models\": [";
  bool first = true;
  for (const TrajectorySplit& s : fit.splits) {
    for (const TrajectoryModel& m : s.models) {
      o << (first ? "" : ", ") << "{\"name\": " << json::string(m.name)
        << ", \"engine\": " << json::string(m.engine) << ", \"split\": " << json::string(m.split)
        << ", \"train\": " << s.train.size() << ", \"test\": " << s.test.size()
        << ", \"median\": " << json::number(m.points.median)
        << ", \"iqr\": " << json::number(m.points.q3 - m.points.q1)
        << ", \"q1\": " << json::number(m.points.q1) << ", \"q3\": " << json::number(m.points.q3)
        << ", \"centre_m\": " << quartiles_json(m.centre)
        << ", \"angle_rad\": " << quartiles_json(m.angle) << ", \"failed\": " << m.failed
        << ", \"parameters\": {";
      for (size_t i = 0; i < m.parameters.size(); ++i)
        o << (i ? ", " : "") << json::string(m.parameters[i].first) << ": "
          << json::number(m.parameters[i].second);
      o << "}";
      if (m.dt > 0.0) o << ", \"dt\": " << json::number(m.dt);
      if (m.evaluations > 0)
        o << ", \"train_median\": " << json::number(m.train_median)
          << ", \"evaluations\": " << m.evaluations;
      o << "}";
      first = false;
    }
  }
  o << "], \"step_checks\": [";
  for (size_t i = 0; i < fit.splits.size(); ++i) {
    const TrajectorySplit::StepCheck& c = fit.splits[i].step_check;
    o << (i ? ", " : "") << "{\"split\": " << json::string(fit.splits[i].split)
      << ", \"omega_dt\": " << json::number(c.omega_dt) << ", \"dt\": " << json::number(c.dt)
      << ", \"median\": " << json::number(c.median)
      << ", \"apart_median\": " << json::number(c.apart) << "}";
  }
  o << "]}\n";
  return o.str();
}

std::string trajectory_fit_text(const TrajectoryFit& fit) {
  std::ostringstream o;
  o << fit.recording << ": " << fit.trajectories << " trajectories, the first "
    << format_number("%g", fit.window) << " s of each (" << fit.samples << " samples or more); "
    << fit.lifted << " first samples penetrated and were lifted to touch";
  if (fit.lifted > 0) o << " (median " << format_number("%.3g", fit.median_lift * 1e3) << " mm)";
  o << "; fitted in " << format_number("%.1f", fit.seconds) << " s\n";
  o << "error of one trajectory: " << kMetric << "; median [IQR] over the held-out half, "
    << "beside the largest centre distance (m) and angle difference (rad)\n";
  for (const TrajectorySplit& s : fit.splits) {
    o << "\n"
      << s.split << " split (" << s.train.size() << " to fit, " << s.test.size() << " held out)\n";
    o << "  model       engine    median  [q1, q3]          centre  angle   parameters\n";
    for (const TrajectoryModel& m : s.models) {
      std::string params;
      for (size_t i = 0; i < m.parameters.size(); ++i)
        params += (i ? ", " : "") + m.parameters[i].first + " " +
                  format_number("%.4g", m.parameters[i].second);
      if (m.dt > 0.0) params += ", dt " + format_number("%.3g", m.dt);
      if (m.failed > 0) params += "; " + std::to_string(m.failed) + " replays stopped";
      o << "  " << m.name << std::string(m.name.size() < 12 ? 12 - m.name.size() : 1, ' ')
        << m.engine << std::string(m.engine.size() < 10 ? 10 - m.engine.size() : 1, ' ')
        << format_number("%.4f", m.points.median) << "  [" << format_number("%.4f", m.points.q1)
        << ", " << format_number("%.4f", m.points.q3) << "]  "
        << format_number("%.4f", m.centre.median) << "  " << format_number("%.3f", m.angle.median)
        << "   " << params << "\n";
    }
    const TrajectorySplit::StepCheck& c = s.step_check;
    o << "  the penalty fit at omega dt = " << format_number("%g", c.omega_dt) << " (dt "
      << format_number("%.3g", c.dt) << " s): median " << format_number("%.4f", c.median)
      << "; apart from the replay above by " << format_number("%.4f", c.apart)
      << " m (median, same metric)\n";
  }
  o << "\nk (N/m) and c (N s/m) are for the recording's mass (" << format_number("%g", fit.mass)
    << " kg); the peer's replay is read from its file, not fitted here\n";
  return o.str();
}

}  // namespace contact2d::analysis
