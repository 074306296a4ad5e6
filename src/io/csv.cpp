// Trajectory CSV rows (io/csv.hpp).
#include "io/csv.hpp"

#include <cstdio>

namespace contact2d {

void write_trajectory_row(std::FILE* out, const Sample& s) {
  std::fprintf(out, "%.10g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", s.t, s.state.q.x(),
               s.state.q.y(), s.state.q.z(), s.state.v.x(), s.state.v.y(), s.state.v.z());
}

}  // namespace contact2d
