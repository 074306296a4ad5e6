#include <sstream>
#include <string>
#include <vector>

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
  return json::object({{"median", q.median}, {"iqr", q.q3 - q.q1}, {"q1", q.q1}, {"q3", q.q3}});
}

// `"key": value` members joined into one object.
std::string members(const std::vector<std::string>& fields) {
  std::string out = "{";
  for (size_t i = 0; i < fields.size(); ++i) out += (i ? ", " : "") + fields[i];
  return out + "}";
}

std::string member(const char* key, const std::string& json_value) {
  return json::string(key) + ": " + json_value;
}

std::string model_json(const TrajectorySplit& s, const TrajectoryModel& m) {
  std::vector<std::string> f = {member("name", json::string(m.name)),
                                member("engine", json::string(m.engine)),
                                member("split", json::string(m.split)),
                                member("train", std::to_string(s.train.size())),
                                member("test", std::to_string(s.test.size())),
                                member("median", json::number(m.points.median)),
                                member("iqr", json::number(m.points.q3 - m.points.q1)),
                                member("q1", json::number(m.points.q1)),
                                member("q3", json::number(m.points.q3)),
                                member("centre_m", quartiles_json(m.centre)),
                                member("angle_rad", quartiles_json(m.angle)),
                                member("failed", std::to_string(m.failed)),
                                member("parameters", json::object(m.parameters))};
  if (m.dt > 0.0) f.push_back(member("dt", json::number(m.dt)));
  if (m.evaluations > 0) {
    f.push_back(member("train_median", json::number(m.train_median)));
    f.push_back(member("evaluations", std::to_string(m.evaluations)));
  }
  return members(f);
}

std::string split_json(const TrajectorySplit& s) {
  const TrajectorySplit::StepCheck& c = s.step_check;
  std::string grid = "[";
  for (size_t j = 0; j < s.k_grid.size(); ++j)
    grid += (j ? ", " : "") +
            json::object({{"k", s.k_grid[j].first}, {"train_median", s.k_grid[j].second}});
  grid += "]";
  std::string distances = "[";
  for (size_t j = 0; j < s.engine_distances.size(); ++j)
    distances +=
        (j ? ", " : "") + members({member("a", json::string(s.engine_distances[j].a)),
                                   member("b", json::string(s.engine_distances[j].b)),
                                   member("median", json::number(s.engine_distances[j].median))});
  distances += "]";
  return members({member("split", json::string(s.split)), member("engine_distances", distances),
                  member("step_check", json::object({{"omega_dt", c.omega_dt},
                                                     {"dt", c.dt},
                                                     {"median", c.median},
                                                     {"apart_median", c.apart}})),
                  member("k_grid", grid)});
}

}  // namespace

std::string trajectory_fit_json(const TrajectoryFit& fit) {
  std::string models = "[", splits = "[";
  for (const TrajectorySplit& s : fit.splits) {
    for (const TrajectoryModel& m : s.models)
      models += (models.size() > 1 ? ", " : "") + model_json(s, m);
    splits += (splits.size() > 1 ? ", " : "") + split_json(s);
  }
  return members(
             {member("recording", json::string(fit.recording)),
              member("kind", json::string("trajectories")), member("peer", json::string(fit.peer)),
              member("trajectories", std::to_string(fit.trajectories)),
              member("samples", std::to_string(fit.samples)),
              member("window_s", json::number(fit.window)),
              member("omega_dt", json::number(fit.omega_dt)),
              member("lifted_to_touch", std::to_string(fit.lifted)),
              member("median_lift_m", json::number(fit.median_lift)),
              member("mass", json::number(fit.mass)), member("inertia", json::number(fit.inertia)),
              member("metric", json::string(kMetric)),
              member("seconds", json::number(fit.seconds, 4)), member("models", models + "]"),
              member("splits", splits + "]")}) +
         "\n";
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
        << (params.empty() ? "" : "   " + params) << "\n";
    }
    if (!s.engine_distances.empty()) {
      o << "  engines apart per trajectory (median, same metric):";
      for (const TrajectorySplit::Distance& d : s.engine_distances)
        o << " " << d.a << "-" << d.b << " " << format_number("%.3g", d.median) << ";";
      o << "\n";
    }
    o << "  the grid's best training median at k (zeta, mu over the grid):";
    for (const auto& [k, e] : s.k_grid)
      o << " k " << format_number("%.0e", k) << ": " << format_number("%.4f", e) << ";";
    o << "\n";
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
