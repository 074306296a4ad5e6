// Every command the committed report's "In short" prints
// (validation/report/README.md), run as printed through the program, against
// the figure it stands next to, at the 3 significant digits the page prints
// (issue 48 §6). The commands and the figures are both read from the page:
// the placeholders it names (SCENE, MAPPING, C, sNN) are filled in, `--json`
// is appended, and `--no-diagnosis` where the figure is not the diagnosis's.
// The figures are aggregated by the page's own rules (report/numbers.hpp).
// Not covered: the friction table's "the cone's shape" and "its push" and
// the same two maxima under "Why they still differ": friction.md's method
// (analysis::friction_parts) compares two runs of the reference under two
// friction laws, which no compare command prints.
// About 160 runs of compare, ~20 s on two cores (label replay: not in the
// sanitizer stage).
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/scene.hpp"
#include "io/json_reader.hpp"
#include "io/scene_file.hpp"
#include "report/numbers.hpp"
#include "report/results.hpp"

namespace contact2d::report {
namespace {

const std::string kExe = CONTACT2D_EXE;
const std::string kRoot = CONTACT2D_SOURCE_DIR;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The page's "## In short" section.
std::string in_short() {
  const std::string page = read_text(kRoot + "/validation/report/README.md");
  const size_t begin = page.find("## In short");
  const size_t end = page.find("\n## ", begin + 1);
  return begin == std::string::npos ? std::string() : page.substr(begin, end - begin);
}

// The first match's groups of `pattern` in `text` (empty when none).
std::smatch find(const std::string& text, const std::string& pattern) {
  std::smatch m;
  std::regex_search(text, m, std::regex(pattern));
  return m;
}

std::string replace_all(std::string text, const std::string& what, const std::string& with) {
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + with.size()))
    text.replace(at, what.size(), with);
  return text;
}

std::vector<std::string> split_list(std::string text) {
  text = replace_all(text, " and ", ", ");
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string item; std::getline(s, item, ',');) {
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// One command as printed ("contact2d compare …"), the options appended.
struct PrintedRun {
  std::string command;
  bool diagnosis = false;
  json::Value result;
  std::string output;
};

PrintedRun make_run(const std::string& printed, bool diagnosis) {
  return {printed, diagnosis, {}, {}};
}

void run_all(std::vector<PrintedRun>& runs) {
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i; (i = next++) < runs.size();) {
      PrintedRun& r = runs[i];
      const std::string args = r.command.substr(std::string("contact2d").size());
      const std::string line = "cd " + kRoot + " && " + kExe + args + " --json" +
                               (r.diagnosis ? "" : " --no-diagnosis") + " 2>/dev/null";
      std::FILE* pipe = ::popen(line.c_str(), "r");
      if (!pipe) continue;
      std::array<char, 65536> buffer{};
      for (size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
        r.output.append(buffer.data(), n);
      ::pclose(pipe);
      try {
        r.result = json::parse(r.output, r.command);
      } catch (const std::exception&) {
        r.result = {};
      }
    }
  };
  const unsigned threads = std::max(2U, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
}

double number(const PrintedRun& r, const std::string& key) {
  const json::Value* v = r.result.get(key);
  return v && v->kind == json::Value::Kind::Number ? v->number
                                                   : std::numeric_limits<double>::quiet_NaN();
}

// The diagnosis's friction_law re-run: the distance it leaves.
double friction_law_after(const PrintedRun& r) {
  for (const char* list : {"diagnosis", "ruled_out"}) {
    const json::Value* items = r.result.get(list);
    if (!items) continue;
    for (const json::Value& f : items->items) {
      const json::Value* cause = f.get("cause");
      const json::Value* after = f.get("after");
      if (cause && cause->text == "friction_law" && after) return after->number;
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::string sig(double x) { return format_significant(x); }

// The backticked command of `text` that contains `marker`.
std::string command_with(const std::string& text, const std::string& marker) {
  const std::regex span("`(contact2d [^`]*)`");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), span); it != std::sregex_iterator();
       ++it) {
    if ((*it)[1].str().find(marker) != std::string::npos) return (*it)[1].str();
  }
  return "";
}

TEST(InShort, EveryPrintedCommandReproducesItsFigure) {
  const std::string text = in_short();
  ASSERT_FALSE(text.empty()) << "no In short in validation/report/README.md";
  std::vector<PrintedRun> runs;

  // The recommendation: the geometric means of section 2.
  const std::string mapping_command = command_with(text, "--mapping MAPPING");
  ASSERT_FALSE(mapping_command.empty()) << text;
  const std::smatch lists = find(text, R"(SCENE = ([a-z_, ]+) of the)");
  const std::smatch mapping_list = find(text, R"(MAPPING = ([a-z, ]+)\))");
  ASSERT_FALSE(lists.empty());
  ASSERT_FALSE(mapping_list.empty());
  const std::vector<std::string> scenes = split_list(lists[1]);
  const std::vector<std::string> mappings = split_list(mapping_list[1]);
  const size_t mapping_first = runs.size();
  for (const std::string& s : scenes) {
    for (const std::string& m : mappings) {
      runs.push_back(
          make_run(replace_all(replace_all(mapping_command, "SCENE", s), "MAPPING", m), false));
    }
  }

  // The random scenes, each with and without friction, under each mapping.
  const std::string random_command = command_with(text, "sNN.toml");
  const std::smatch random_adds = find(
      text, R"(add `([^`]*)` for the frictionless columns, `([^`]*)` for the compensated rows)");
  ASSERT_FALSE(random_command.empty());
  ASSERT_FALSE(random_adds.empty());
  const std::string random_dir = random_command.substr(
      std::string("contact2d compare ").size(),
      random_command.find("/sNN.toml") - std::string("contact2d compare ").size());
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kRoot + "/" + random_dir)) {
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  ASSERT_FALSE(names.empty());
  const size_t random_first = runs.size();
  for (const std::string& mapping_add : {std::string(), " " + random_adds[2].str()}) {
    for (const std::string& n : names) {
      const std::string c = replace_all(random_command, "sNN", n) + mapping_add;
      runs.push_back(make_run(c + " " + random_adds[1].str(), false));
      runs.push_back(make_run(c, true));
    }
  }

  // The built-in scenes at each C, without and with friction, and the
  // circle without rolling resistance.
  const std::string goal_command = command_with(text, "contact.c=C");
  const std::smatch c_list =
      find(text, R"(for C = ([0-9, and]+) \(add `([^`]*)` for the frictionless line)");
  const std::smatch no_roll = find(text, R"(with friction the circle also with `([^`]*)`)");
  ASSERT_FALSE(goal_command.empty());
  ASSERT_FALSE(c_list.empty());
  const size_t goal_first = runs.size();
  for (const std::string& c : split_list(c_list[1])) {
    for (const std::string& s : scenes) {
      const std::string g = replace_all(replace_all(goal_command, "SCENE", s), "=C", "=" + c);
      runs.push_back(make_run(g + " " + c_list[2].str(), false));
      runs.push_back(make_run(g, true));
    }
    if (!no_roll.empty()) {
      runs.push_back(
          make_run(replace_all(replace_all(goal_command, "SCENE", "circle"), "=C", "=" + c) + " " +
                       no_roll[1].str(),
                   false));
    }
  }
  const size_t goal_end = runs.size();

  run_all(runs);
  for (const PrintedRun& r : runs)
    ASSERT_TRUE(std::isfinite(number(r, "max_pos_err"))) << r.command << "\n" << r.output;

  // The recommendation's ratio and mapping.
  std::vector<MappingCase> cases;
  for (size_t i = mapping_first; i < random_first; ++i) {
    const size_t k = i - mapping_first;
    MappingCase c{scenes[k / mappings.size()], mappings[k % mappings.size()], {}};
    c.result.max_pos = number(runs[i], "max_pos_err");
    cases.push_back(c);
  }
  const OverallWinner w = overall_winner(mapping_means(cases, scenes, mappings));
  const std::smatch ratio = find(text, R"(is\n([0-9.]+)× below the next best mapping)");
  ASSERT_FALSE(ratio.empty());
  EXPECT_EQ(sig(w.ratio_to_next), ratio[1].str()) << mapping_command;
  const std::smatch closer = find(text, R"(`--mapping ([a-z]+)` comes closer)");
  EXPECT_EQ(w.mapping, closer.empty() ? std::string("calibrated") : closer[1].str());

  // The random scenes' table, band by band, and the friction table.
  // Where the engines agree, no diagnosis runs: the page's soft_cone
  // command at the impratio compare printed.
  const std::smatch soft_add = find(text, R"(no diagnosis runs: add `([^`]*cone_ratio=I)`)");
  ASSERT_FALSE(soft_add.empty()) << text;
  std::vector<PrintedRun> agreeing;
  std::vector<size_t> agreeing_of;
  for (size_t i = random_first; i < goal_end; ++i) {
    const PrintedRun& r = runs[i];
    const json::Value* agrees = r.result.get("agrees");
    if (!r.diagnosis || !agrees || agrees->text != "true") continue;
    std::array<char, 32> impratio{};
    std::snprintf(impratio.data(), impratio.size(), "%.17g", number(r, "impratio"));
    agreeing.push_back(make_run(
        r.command + " " + replace_all(soft_add[1].str(), "=I", "=" + std::string(impratio.data())),
        false));
    agreeing_of.push_back(i);
  }
  run_all(agreeing);
  std::vector<double> rest_of(runs.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t i = random_first; i < goal_end; ++i) rest_of[i] = friction_law_after(runs[i]);
  for (size_t a = 0; a < agreeing.size(); ++a)
    rest_of[agreeing_of[a]] = number(agreeing[a], "max_pos_err");

  const RandomConfig config{0, static_cast<int>(names.size()), 1e-5, 1e-4};
  std::vector<std::vector<RandomCase>> by_mapping(2);
  for (size_t m = 0; m < 2; ++m) {
    for (size_t i = 0; i < names.size(); ++i) {
      const PrintedRun& without = runs[random_first + 2 * (m * names.size() + i)];
      const PrintedRun& with = runs[random_first + 2 * (m * names.size() + i) + 1];
      const Scene scene = load_scene(kRoot + "/" + random_dir + "/" + names[i] + ".toml");
      RandomCase c;
      c.name = names[i];
      c.mass = make_model(scene).body.mass;
      c.k = scene.contact.k;
      c.c = scene.contact.c;
      c.mu = scene.contact.mu;
      c.max_pos_frictionless = number(without, "max_pos_err");
      c.max_angle_frictionless = number(without, "max_angle_err");
      c.max_pos_friction = number(with, "max_pos_err");
      c.friction_rest = rest_of[random_first + 2 * (m * names.size() + i) + 1];
      EXPECT_TRUE(std::isfinite(c.friction_rest)) << with.command << " has no friction_law re-run";
      by_mapping[m].push_back(c);
    }
  }
  const std::regex band_row(
      R"(\n\| (ζ[^|]*|[0-9.]+ ≤ ζ[^|]*) \| ([a-z]+) \| (\d+) \| (\d+) \| (\S+) / (\S+) \| (\S+) \|)");
  std::vector<std::smatch> rows;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), band_row);
       it != std::sregex_iterator(); ++it)
    rows.push_back(*it);
  ASSERT_EQ(rows.size(), 6U) << text;
  const std::vector<ZetaBand> bands[2] = {random_bands(by_mapping[0], config),
                                          random_bands(by_mapping[1], config)};
  for (size_t r = 0; r < rows.size(); ++r) {
    const size_t m = r % 2;
    const ZetaBand& z = bands[m][r / 2];
    const std::smatch& row = rows[r];
    SCOPED_TRACE(row[0].str());
    EXPECT_EQ(row[2].str(), m == 0 ? "calibrated" : "compensated");
    EXPECT_EQ(row[3].str(), std::to_string(z.count));
    EXPECT_EQ(row[4].str(), std::to_string(z.reached));
    EXPECT_EQ(row[5].str(), sig(z.median_pos));
    EXPECT_EQ(row[6].str(), sig(z.max_pos));
    EXPECT_EQ(row[7].str(), sig(z.max_pos_friction));
  }
  const std::regex parts_row(
      R"(\n\| (calibrated|compensated) \| (\S+) \| (\d+) of (\d+) \| \S+ \| \S+ \| (\S+) \(largest (\S+)\) \| (\d+) of (\d+) \|)");
  size_t parts_seen = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), parts_row);
       it != std::sregex_iterator(); ++it, ++parts_seen) {
    const std::smatch& row = *it;
    SCOPED_TRACE(row[0].str());
    const FrictionSummary f = friction_summary(by_mapping[row[1] == "calibrated" ? 0 : 1], 1e-3);
    EXPECT_EQ(row[2].str(), sig(f.median_total));
    EXPECT_EQ(row[3].str(), std::to_string(f.within));
    EXPECT_EQ(row[4].str(), std::to_string(f.count));
    EXPECT_EQ(row[5].str(), sig(f.median_rest));
    EXPECT_EQ(row[6].str(), sig(f.max_rest));
    EXPECT_EQ(row[7].str(), std::to_string(f.rest_within));
  }
  EXPECT_EQ(parts_seen, 2U) << text;

  // The built-in scenes: the frictionless and the friction lines, and the
  // reference under MuJoCo's law (the diagnosis's friction_law re-run).
  double frictionless = 0.0, friction = 0.0, rest = 0.0;
  int reached = 0, count = 0;
  for (size_t i = goal_first; i < goal_end; ++i) {
    const PrintedRun& r = runs[i];
    const bool without = r.command.find(c_list[2].str()) != std::string::npos;
    const double pos = number(r, "max_pos_err");
    if (without) {
      frictionless = std::max(frictionless, pos);
      ++count;
      reached += goal_reached(pos, number(r, "max_angle_err"), config.pos_goal, config.angle_goal);
    } else {
      friction = std::max(friction, pos);
      if (r.diagnosis) rest = std::max(rest, rest_of[i]);
    }
  }
  const std::smatch builtin = find(
      text,
      R"(without friction (\d+) of (\d+) cases within \S+ m and \S+ rad \(largest (\S+) m\), with friction up to (\S+) m apart)");
  ASSERT_FALSE(builtin.empty()) << text;
  EXPECT_EQ(builtin[1].str(), std::to_string(reached));
  EXPECT_EQ(builtin[2].str(), std::to_string(count));
  EXPECT_EQ(builtin[3].str(), sig(frictionless)) << goal_command << " " << c_list[2].str();
  EXPECT_EQ(builtin[4].str(), sig(friction)) << goal_command;
  const std::smatch soft = find(text, R"(they are at most (\S+) m apart)");
  ASSERT_FALSE(soft.empty());
  EXPECT_EQ(soft[1].str(), sig(rest));
  const std::smatch rest_why = find(text, R"(MuJoCo's step\) is at most (\S+) m;)");
  ASSERT_FALSE(rest_why.empty());
  EXPECT_EQ(rest_why[1].str(), sig(rest));
}

}  // namespace
}  // namespace contact2d::report
