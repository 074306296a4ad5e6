#include "io/plot.hpp"

#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/input_error.hpp"
#include "io/csv.hpp"

namespace contact2d {
namespace {

// Columns: t, x, y, θ (ref), x, y, θ (MuJoCo), position error, angle error.
// Errors of exactly 0 are written as 1e-300 so the log axis keeps them.
void write_data(std::FILE* out, const Trajectory& ref, const Trajectory& mj) {
  const size_t n = std::min(ref.samples.size(), mj.samples.size());
  for (size_t i = 0; i < n; ++i) {
    const State& a = ref.samples[i].state;
    const State& b = mj.samples[i].state;
    const double pos = std::max((a.q.head<2>() - b.q.head<2>()).norm(), 1e-300);
    const double angle = std::max(std::abs(a.q.z() - b.q.z()), 1e-300);
    std::fprintf(out, "%.9g %.12g %.12g %.12g %.12g %.12g %.12g %.6g %.6g\n", ref.samples[i].t,
                 a.q.x(), a.q.y(), a.q.z(), b.q.x(), b.q.y(), b.q.z(), pos, angle);
  }
}

std::string script(const std::string& data, const std::string& png, const std::string& title) {
  const std::string d = "'" + data + "'";
  return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo size 1200,900 } "
         "else { set terminal png size 1200,900 }\n"
         "set output '" +
         png +
         "'\n"
         "set multiplot layout 2,2 title '" +
         title +
         "'\n"
         "set xlabel 't (s)'\nset grid\nset key top right\n"
         "set ylabel 'x (m)'\nplot " +
         d + " u 1:2 w l lw 2 t 'ref', " + d +
         " u 1:5 w l dt 2 lw 2 t 'MuJoCo'\n"
         "set ylabel 'y (m)'\nplot " +
         d + " u 1:3 w l lw 2 t 'ref', " + d +
         " u 1:6 w l dt 2 lw 2 t 'MuJoCo'\n"
         "set ylabel 'theta (rad)'\nplot " +
         d + " u 1:4 w l lw 2 t 'ref', " + d +
         " u 1:7 w l dt 2 lw 2 t 'MuJoCo'\n"
         "set logscale y\nset format y '10^{%L}'\nset yrange [1e-12:*]\nset ylabel 'error'\n"
         "plot " +
         d + " u 1:8 w l lw 2 t 'position (m)', " + d +
         " u 1:9 w l lw 2 t 'angle (rad)'\n"
         "unset multiplot\n";
}

void require_quotable(const std::string& text, const std::string& what) {
  if (text.find('\'') != std::string::npos || text.find('\n') != std::string::npos) {
    throw InputError(what + " '" + text +
                     "' must not contain a single quote or newline (gnuplot script)");
  }
}

}  // namespace

void plot_comparison(const std::string& png_path, const std::string& title, const Trajectory& ref,
                     const Trajectory& mujoco) {
  require_quotable(png_path, "--plot");
  require_quotable(title, "plot title");
  AtomicFile png(png_path);             // gnuplot writes here; renamed on success
  AtomicFile data(png_path + ".data");  // never committed: removed on return
  write_data(data.get(), ref, mujoco);
  if (std::fflush(data.get()) != 0) throw InputError(data.temp_path() + ": cannot write plot data");
  run_gnuplot(script(data.temp_path(), png.temp_path(), title), png_path);
  png.commit();
}

void run_gnuplot(const std::string& script, const std::string& png_path) {
  // gnuplot's own warnings go to stderr; stdout stays the command's.
  std::FILE* pipe = ::popen("gnuplot >/dev/null", "w");
  if (!pipe) throw InputError(png_path + ": cannot start gnuplot");
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int raw = ::pclose(pipe);
  const int status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 1;
  if (status == 127)
    throw InputError(png_path + ": gnuplot not found (install Debian package gnuplot-nox)");
  if (status != 0) {
    throw InputError(png_path + ": gnuplot failed (exit status " + std::to_string(status) + ")");
  }
}

std::string gnuplot_quoted(const std::string& path) {
  if (path.find('\'') != std::string::npos || path.find('\n') != std::string::npos) {
    throw InputError(path + ": a plot path must not contain a quote or newline");
  }
  return "'" + path + "'";
}

std::string gnuplot_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&') out += '\\';
    if (c == '\'') {
      out += "''";
      continue;
    }
    out += c;
  }
  return out;
}

}  // namespace contact2d
