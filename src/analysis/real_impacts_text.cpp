#include <cmath>
#include <sstream>

#include "analysis/real_impacts.hpp"
#include "core/format.hpp"
#include "io/json.hpp"

namespace contact2d::analysis {

std::string impact_fit_json(const ImpactFit& fit) {
  std::ostringstream o;
  o << "{\"recording\": " << json::string(fit.recording) << ", \"impacts\": " << fit.impacts.size()
    << ", \"flagged_left_out\": " << fit.flagged_left_out
    << ", \"lifted_to_first_touch\": " << fit.lifted
    << ", \"median_lift_m\": " << json::number(fit.median_lift)
    << ", \"mass\": " << json::number(fit.mass) << ", \"inertia\": " << json::number(fit.inertia)
    << ", \"metric\": \"|W(v_hat - v)| / |W v| over (vx, vy, omega) after the impact, W = diag(1, "
       "1, sqrt(I/m))\""
    << ", \"seconds\": " << json::number(fit.seconds, 4) << ", \"models\": [";
  bool first = true;
  for (const SplitFit& s : fit.splits) {
    for (const ModelFit& m : s.models) {
      o << (first ? "" : ", ") << "{\"name\": " << json::string(m.name)
        << ", \"engine\": " << json::string(m.engine) << ", \"split\": " << json::string(m.split)
        << ", \"train\": " << s.train.size() << ", \"test\": " << s.test.size()
        << ", \"median\": " << json::number(m.median) << ", \"iqr\": " << json::number(m.iqr())
        << ", \"q1\": " << json::number(m.q1) << ", \"q3\": " << json::number(m.q3)
        << ", \"failed_replays\": " << m.failed_replays
        << ", \"unseparated_replays\": " << m.unseparated_replays
        << ", \"parameters\": " << json::object(m.parameters);
      if (!m.spread.empty()) {
        o << ", \"spread_16_84\": {";
        for (size_t i = 0; i < m.spread.size(); ++i)
          o << (i ? ", " : "") << json::string(m.parameters[i].first) << ": ["
            << json::number(m.spread[i].first) << ", " << json::number(m.spread[i].second) << "]";
        o << "}";
      }
      if (m.replay_window > 0.0) o << ", \"replay_window_s\": " << json::number(m.replay_window);
      if (m.evaluations > 0)
        o << ", \"train_median\": " << json::number(m.train_median)
          << ", \"evaluations\": " << m.evaluations;
      o << "}";
      first = false;
    }
  }
  o << "], \"splits\": [";
  for (size_t i = 0; i < fit.splits.size(); ++i) {
    const SplitFit& s = fit.splits[i];
    o << (i ? ", " : "") << "{\"split\": " << json::string(s.split) << ", \"engine_distances\": [";
    for (size_t j = 0; j < s.engine_distances.size(); ++j)
      o << (j ? ", " : "") << "{\"a\": " << json::string(s.engine_distances[j].a)
        << ", \"b\": " << json::string(s.engine_distances[j].b)
        << ", \"median\": " << json::number(s.engine_distances[j].median) << "}";
    o << "], \"spin_slope\": " << json::number(s.spin_slope)
      << ", \"spin_intercept\": " << json::number(s.spin_intercept) << ", \"k_profile\": [";
    for (size_t j = 0; j < s.k_profile.size(); ++j)
      o << (j ? ", " : "") << "{\"k\": " << json::number(s.k_profile[j].first)
        << ", \"train_median\": " << json::number(s.k_profile[j].second) << "}";
    o << "]}";
  }
  o << "]}\n";
  return o.str();
}

std::string impact_fit_text(const ImpactFit& fit) {
  std::ostringstream o;
  o << fit.recording << ": " << fit.impacts.size() << " impacts (" << fit.flagged_left_out
    << " flagged by the recording left out); " << fit.lifted
    << " pre-impact states penetrated and were lifted to first touch (median "
    << format_number("%.3g", fit.median_lift * 1e3) << " mm); fitted in "
    << format_number("%.1f", fit.seconds) << " s\n";
  o << "error of one impact: |W(v_hat - v)| / |W v| over (vx, vy, omega) after it, W = diag(1, 1, "
       "sqrt(I/m)); median [IQR] over the held-out half\n";
  for (const SplitFit& s : fit.splits) {
    o << "\n"
      << s.split << " split (" << s.train.size() << " to fit, " << s.test.size() << " held out)\n";
    o << "  model                 engine    median  [q1, q3]          parameters\n";
    for (const ModelFit& m : s.models) {
      std::string params;
      for (size_t i = 0; i < m.parameters.size(); ++i) {
        params += (i ? ", " : "") + m.parameters[i].first + " " +
                  format_number("%.4g", m.parameters[i].second);
        if (i < m.spread.size())
          params += " (" + format_number("%.3g", m.spread[i].first) + "-" +
                    format_number("%.3g", m.spread[i].second) + ")";
      }
      o << "  " << m.name << std::string(m.name.size() < 22 ? 22 - m.name.size() : 1, ' ')
        << m.engine << std::string(m.engine.size() < 10 ? 10 - m.engine.size() : 1, ' ')
        << format_number("%.3f", m.median) << "  [" << format_number("%.3f", m.q1) << ", "
        << format_number("%.3f", m.q3) << "]    " << params
        << (m.failed_replays > 0 ? "  (" + std::to_string(m.failed_replays) +
                                       " replays did not finish: each counted as error 10)"
                                 : std::string())
        << (m.unseparated_replays > 0 ? "  (" + std::to_string(m.unseparated_replays) +
                                            " replays still on the ground after " +
                                            format_number("%.3g", m.replay_window) +
                                            " s, 8 undamped half-periods: each counted as error 10)"
                                      : std::string())
        << "\n";
    }
    if (!s.engine_distances.empty()) {
      o << "  engines apart per impact (median, same metric):";
      for (const SplitFit::Distance& d : s.engine_distances)
        o << " " << d.a << "-" << d.b << " " << format_number("%.3g", d.median) << ";";
      o << "\n";
    }
    if (std::isfinite(s.spin_slope) && std::isfinite(s.spin_intercept)) {
      o << "  held out, the spin changes by " << format_number("%.2f", s.spin_slope)
        << " x what a point impulse at the lowest point would give with the measured dv, plus "
        << format_number("%.3g", s.spin_intercept) << " rad/s (least squares)\n";
    } else {
      // Every held-out impact gives the same point impulse (vertical drops
      // through the centre: none turns it): no line to fit, as the JSON's null.
      o << "  held out, the spin's change is not fitted: the point impulses at the lowest "
           "point are all alike (no spread to fit a line through)\n";
    }
    if (!s.k_profile.empty()) {
      o << "  k profile (training median error, zeta, mu, mu_roll refitted):";
      for (const auto& [k, e] : s.k_profile)
        o << " k " << format_number("%.0e", k) << ": " << format_number("%.4f", e) << ";";
      o << "\n";
    }
  }
  o << "\nspreads in parentheses: 16th-84th percentile of bootstrap refits on resampled training "
       "sets\n";
  return o.str();
}

}  // namespace contact2d::analysis
