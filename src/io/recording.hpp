// A recording of a real planar body (docs/recordings.md defines the format):
// a manifest (TOML) naming the body as a scene file does, and a CSV of
// measured states. Two kinds:
//   impacts       one row per impact: the state just before the body touches
//                 and just after it leaves (x0 … omega0, x1 … omega1)
//   trajectories  one row per sample: traj, t, x, y, theta, vx, vy, omega,
//                 t increasing within each trajectory; optionally a peer
//                 engine's replay of the same trajectories (peer_csv), whose
//                 vx, vy, omega may be left out (all three)
// Reading checks every field (a number, finite), every column (present),
// the time order and that there is something to read; each failure is one
// InputError line naming the file, the row (its line number) and the field.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"

namespace contact2d {

struct RecordedImpact {
  int id = 0;         // the CSV's `impact` column
  int line = 0;       // its line in the CSV (the header is line 1)
  State before;       // just before the body touches
  State after;        // just after it leaves
  std::string flags;  // the `flags` column when there is one, else empty
};

struct RecordedTrajectory {
  int id = 0;              // the CSV's `traj` column
  int line = 0;            // line of its first row
  bool velocities = true;  // false: the file gave poses only (a peer's), v = 0
  std::vector<int> lines;  // line of each sample
  std::vector<double> t;
  std::vector<State> states;
};

struct Recording {
  std::string path;  // the manifest
  std::string kind;  // "impacts" or "trajectories"
  Scene body;        // shape, mass, dimensions and gravity (sim.gravity) of the recorded body
  double frame_rate = 0.0;  // Hz
  std::string csv;          // the data file's path as read
  std::string peer_csv;     // the peer's data file's path as read, or empty
  std::vector<RecordedImpact> impacts;
  std::vector<RecordedTrajectory> trajectories;
  std::string peer;  // the peer engine's name ("PyBullet"), or empty
  std::vector<RecordedTrajectory> peer_trajectories;  // same ids as `trajectories`
  std::string citation, licence;                      // [source]
};

// Reads the manifest at `path` and its CSV (paths relative to the manifest).
Recording read_recording(const std::string& path);

}  // namespace contact2d
