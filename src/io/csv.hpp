// Trajectory CSV (docs/cli.md): its header and one row per sample. The file
// itself is written atomically (io/atomic_file.hpp), so a run that fails or
// diverges leaves no file behind.
#pragma once

#include <cstdio>

#include "core/run.hpp"

namespace contact2d {

constexpr const char* kTrajectoryHeader = "t,x,y,theta,vx,vy,omega";

void write_trajectory_row(std::FILE* out, const Sample& sample);

}  // namespace contact2d
