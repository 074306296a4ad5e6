// The extreme matrix through the real program: every body × contact
// stiffness k from 1e3 to 1e9 N/m × impact speed 0.1 to 100 m/s × mass 1e-6
// to 1e6 kg × every integrator × both engines (MuJoCo has no explicit
// Euler). Each scene is written as a TOML file, as a user would, with the
// damping ratio held at ζ = 0.1 (c = 2ζ·√(k·m)), the body's lowest point 1 cm
// above the ground, Δt = 1e-4 s and 0.05 s of simulated time (the impact and
// its first rebounds; 500 steps keep the 1,000-odd runs fast).
//
// Under the sanitizers (scripts/test's second build) each run is a process
// whose start alone takes ~0.15-0.2 s, and the 1,008 runs were 489 s of a
// 1,414 s stage (35 %), all of it the same code with other numbers. There
// the matrix keeps every body, integrator and engine at the corners of its
// cube, k ∈ {1e3, 1e9}, speed ∈ {0.1, 100}, mass ∈ {1e-6, 1e6}: 224 runs,
// both exit statuses among them (printed); the whole matrix runs in the
// Release stage.
//
// Every run must end as a user can rely on: exit 0 (done; at most one
// warning line on stderr) or 3 (diverged: exactly one line), never anything
// else; the CSV of a finished run has no NaN or inf; a diverged run leaves no
// file. The counts are printed (and quoted in the closing note).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/files.hpp"

namespace fs = std::filesystem;

namespace {

using contact2d::test::read_file;

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

// The scene as TOML: body of mass m, falling at speed v from 1 cm.
std::string scene_text(const std::string& shape, double k, double v, double m) {
  const double c = 2.0 * 0.1 * std::sqrt(k * m);
  std::string body, y;
  if (shape == "point_mass") {
    body = "mass = " + number(m) + "\nhalf_height = 0.05\n";
    y = "0.06";
  } else if (shape == "box") {
    body = "mass = " + number(m) + "\nwidth = 0.4\nheight = 0.2\n";
    y = "0.11";
  } else if (shape == "circle") {
    body = "mass = " + number(m) + "\nradius = 0.1\n";
    y = "0.11";
  } else {  // the default T, its parts' masses scaled to m
    body =
        "parts = [\n  { width = 0.6, height = 0.1, x = 0.0, y = 0.25, mass = " + number(0.6 * m) +
        " },\n  { width = 0.1, height = 0.4, x = 0.0, y = 0.0, mass = " + number(0.4 * m) +
        " },\n]\n";
    y = "0.35";  // COM 0.1 above the stem's centre: stem bottom 0.01 above the ground
  }
  return "scene = \"" + shape + "\"\n[body]\n" + body + "[contact]\nk = " + number(k) +
         "\nc = " + number(c) + "\nmu = 0.5\nalpha = 100\ndamping = \"kelvin_voigt\"\n" +
         "[initial]\ny = " + y + "\nvx = 0.3\nvy = " + number(-v) +
         "\n[sim]\ndt = 1e-4\nduration = 0.05\n";
}

TEST(ExtremeMatrix, EveryRunExitsCleanlyWithoutNaNOrLeftoverFiles) {
  const fs::path dir =
      fs::temp_directory_path() / ("contact2d_extreme_matrix_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<std::string> shapes{"point_mass", "box", "tshape", "circle"};
#ifdef CONTACT2D_SANITIZED
  const std::vector<double> ks{1e3, 1e9};
  const std::vector<double> speeds{0.1, 100.0};
  const std::vector<double> masses{1e-6, 1e6};
#else
  const std::vector<double> ks{1e3, 1e5, 1e7, 1e9};
  const std::vector<double> speeds{0.1, 10.0, 100.0};
  const std::vector<double> masses{1e-6, 1.0, 1e6};
#endif
  const std::vector<std::string> integrators{"explicit_euler", "semi_implicit_euler",
                                             "implicit_euler", "rk4"};
  std::vector<std::string> engines{"ref"};
#ifdef CONTACT2D_WITH_MUJOCO
  engines.push_back("mujoco");
#endif
  std::map<std::string, int> counts;  // "engine exit N"
  int runs = 0;
  for (const std::string& shape : shapes)
    for (double k : ks)
      for (double v : speeds)
        for (double m : masses) {
          const fs::path scene = dir / "scene.toml";
          std::ofstream(scene) << scene_text(shape, k, v, m);
          for (const std::string& engine : engines)
            for (const std::string& integrator : integrators) {
              if (engine == "mujoco" && integrator == "explicit_euler") continue;
              const fs::path csv = dir / "out.csv", err = dir / "stderr.txt";
              fs::remove(csv);
              const std::string what = shape + " k=" + number(k) + " v=" + number(v) +
                                       " m=" + number(m) + " " + engine + " " + integrator;
              const std::string command = std::string("'") + CONTACT2D_EXE + "' simulate '" +
                                          scene.string() + "' --engine " + engine +
                                          " --integrator " + integrator + " --csv '" +
                                          csv.string() + "' >/dev/null 2>'" + err.string() + "'";
              const int raw = std::system(command.c_str());
              ++runs;
              ASSERT_TRUE(WIFEXITED(raw)) << what << ": killed";
              const int status = WEXITSTATUS(raw);
              ++counts[engine + " exit " + std::to_string(status)];
              const std::string text = read_file(err);
              const auto lines = std::count(text.begin(), text.end(), '\n');
              EXPECT_TRUE(status == 0 || status == 3)
                  << what << ": exit " << status << ": " << text;
              if (status == 3) {
                EXPECT_EQ(lines, 1) << what << ": " << text;
                EXPECT_FALSE(fs::exists(csv)) << what << ": a diverged run left its CSV";
              } else if (status == 0) {
                EXPECT_LE(lines, 1) << what << ": " << text;
                const std::string data = read_file(csv);
                EXPECT_EQ(data.find("nan"), std::string::npos) << what << ": NaN in the CSV";
                EXPECT_EQ(data.find("inf"), std::string::npos) << what << ": inf in the CSV";
              }
              for (const auto& entry : fs::directory_iterator(dir)) {
                const std::string name = entry.path().filename().string();
                EXPECT_TRUE(name == "scene.toml" || name == "out.csv" || name == "stderr.txt")
                    << what << ": left " << name;
              }
            }
        }
  std::printf("extreme matrix: %d runs;", runs);
  for (const auto& [key, n] : counts) std::printf(" %s: %d;", key.c_str(), n);
  std::printf("\n");
  fs::remove_all(dir);
}

}  // namespace
