// The one gnuplot runner: what gnuplot prints on stderr reaches contact2d's
// stderr (the CLI test that every plot draws silently relies on it), and
// the helpers every plot script uses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/input_error.hpp"
#include "io/plot.hpp"
#include "support/needs.hpp"

namespace fs = std::filesystem;

namespace contact2d {
namespace {

bool have_gnuplot() { return std::system("gnuplot --version >/dev/null 2>&1") == 0; }

fs::path temp_png(const char* name) {
  return fs::temp_directory_path() /
         (std::string("contact2d_test_plot_") + name + std::to_string(::getpid()) + ".png");
}

TEST(RunGnuplot, PassesOnWhatGnuplotPrintsOnStderr) {
  CONTACT2D_NEEDS(have_gnuplot(), "no gnuplot");
  const fs::path png = temp_png("warn");
  // A constant curve with the y range left to autoscale: gnuplot warns
  // "empty y range [1:1], adjusting to [0.99:1.01]".
  const std::string script = gnuplot_png(png.string(), 200, 100) + "plot 1 notitle\n";
  testing::internal::CaptureStderr();
  run_gnuplot(script, png.string());
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("contact2d: gnuplot warning drawing " + png.string()), std::string::npos)
      << err;
  EXPECT_NE(err.find("empty y range"), std::string::npos) << err;
  fs::remove(png);
}

TEST(RunGnuplot, SilentOnACleanScriptAndNamesThePlotOnFailure) {
  CONTACT2D_NEEDS(have_gnuplot(), "no gnuplot");
  const fs::path png = temp_png("clean");
  testing::internal::CaptureStderr();
  run_gnuplot(gnuplot_png(png.string(), 200, 100) + gnuplot_range("y", 1.0, 1.0, false) +
                  "plot 1 notitle\n",
              png.string());
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_TRUE(fs::exists(png));
  fs::remove(png);
  try {
    run_gnuplot("plot no_such_function(x)\n", "named.png");
    FAIL() << "gnuplot accepted an undefined function";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("named.png: gnuplot failed", 0), 0u) << e.what();
  }
}

TEST(GnuplotText, EscapesEnhancedTextSoNamesReadAsWritten) {
  EXPECT_EQ(gnuplot_text("point_mass"), "point\\_mass");
  EXPECT_EQ(gnuplot_text("a^b {c} @d &e"), "a\\^b \\{c\\} \\@d \\&e");
  EXPECT_EQ(gnuplot_text("it's"), "it''s");
}

TEST(GnuplotRange, NeverEmptyAndPadded) {
  EXPECT_EQ(gnuplot_range("y", 2.0, 2.0, false),
            "set yrange [1.8999999999999999:2.1000000000000001]\nset ytics autofreq\n");
  EXPECT_EQ(gnuplot_range("y", 0.0, 0.0, false), "set yrange [-0.001:0.001]\nset ytics autofreq\n");
  EXPECT_EQ(gnuplot_range("x", 1e-3, 1e-3, true),
            "set xrange [0.00033333333333333332:0.0030000000000000001]\n"
            "set xtics (0.0005, 0.001, 0.002)\nset format x '%g'\n");
  EXPECT_EQ(gnuplot_range("x", 0.0, 1.0, true), "set xrange [1e-16:1]\n");  // log of 0: a default
  EXPECT_EQ(
      gnuplot_range("y", 1e-6, 1e-2, true),
      "set yrange [4.9999999999999998e-07:0.02]\nset ytics autofreq\nset format y '10^{%L}'\n");
}

// Labels of lines that nearly coincide are pushed apart to the gap and
// keep their order; one alone stays where its line is; none rises above
// the top. (The stability map's theory labels: RK4's 2.79 and explicit
// Euler's 2.0 at ζ = 1 are 0.03 apart on its ω·Δt axis.)
TEST(PlotLabels, SpreadKeepsOrderAndGap) {
  const std::vector<double> at = spread_labels({0.50, 0.49, 0.10, 0.97, 0.985}, 0.035, 0.98);
  ASSERT_EQ(at.size(), 5u);
  EXPECT_EQ(at[2], 0.10);   // alone: unmoved
  EXPECT_LT(at[1], at[0]);  // order kept
  EXPECT_GE(at[0] - at[1], 0.035 - 1e-12);
  EXPECT_LE(at[4], 0.98);
  EXPECT_GE(at[4] - at[3], 0.035 - 1e-12);
  EXPECT_GE(at[3] - at[0], 0.035 - 1e-12);
}

// A log axis: the fraction of gnuplot_range's padded range (lo/2, 2·hi),
// and values that have no logarithm become gnuplot's missing value.
TEST(PlotLabels, LogAxisFractionAndMissingValues) {
  EXPECT_NEAR(log_axis_fraction(1.0, 1.0, 100.0), std::log10(2.0) / std::log10(400.0), 1e-15);
  EXPECT_NEAR(log_axis_fraction(10.0, 1.0, 100.0), 0.5, 1e-15);
  EXPECT_EQ(log_axis_value(0.0), "?");
  EXPECT_EQ(log_axis_value(-1e-3), "?");
  EXPECT_EQ(log_axis_value(std::nan("")), "?");
  EXPECT_EQ(log_axis_value(2.5e-7), "2.5e-07");
}

}  // namespace
}  // namespace contact2d
