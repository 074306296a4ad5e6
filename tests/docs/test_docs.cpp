// The documentation stands on its own and says what the program does:
//   - every link in README.md and docs/*.md is a relative path to a file or
//     folder inside the repository (no web address, nothing outside the
//     tree, no missing target);
//   - docs/cli.md names every option that `contact2d --help` and
//     `contact2d COMMAND --help` print.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/files.hpp"

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = fs::weakly_canonical(CONTACT2D_SOURCE_DIR);

using contact2d::test::read_file;

std::vector<fs::path> pages() {
  std::vector<fs::path> out{kRoot / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") out.push_back(entry.path());
  return out;
}

// Markdown links and images outside code spans and fenced blocks:
// "](target)" with an optional "#anchor" and title.
std::vector<std::string> links(const std::string& text) {
  std::vector<std::string> out;
  bool fenced = false;
  std::istringstream lines(text);
  const std::regex link(R"(\]\(([^)\s]+)(?:\s+"[^"]*")?\))");
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (fenced) continue;
    // Drop code spans: a link written as code is not a link.
    std::string prose;
    bool code = false;
    for (char ch : line) {
      if (ch == '`')
        code = !code;
      else if (!code)
        prose += ch;
    }
    for (std::sregex_iterator it(prose.begin(), prose.end(), link), end; it != end; ++it)
      out.push_back((*it)[1]);
  }
  return out;
}

TEST(Docs, EveryLinkIsARelativePathToAFileInTheRepository) {
  int checked = 0;
  for (const fs::path& page : pages()) {
    for (const std::string& target : links(read_file(page))) {
      SCOPED_TRACE(page.string() + ": " + target);
      EXPECT_EQ(target.find("://"), std::string::npos)
          << "a web address: the docs must stand alone";
      EXPECT_NE(target.rfind("mailto:", 0), 0u);
      const std::string path = target.substr(0, target.find('#'));
      if (path.empty()) continue;  // an anchor on the same page
      EXPECT_NE(path[0], '/') << "an absolute path";
      const fs::path resolved = fs::weakly_canonical(page.parent_path() / path);
      const std::string inside = fs::relative(resolved, kRoot).string();
      EXPECT_FALSE(inside.rfind("..", 0) == 0) << "outside the repository: " << resolved;
      EXPECT_TRUE(fs::exists(resolved)) << "missing: " << resolved;
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);  // the pages do link to each other
}

TEST(Docs, LinkFinderSeesLinksAndIgnoresCode) {
  const auto found = links("a [b](docs/x.md) `[c](y.md)` ![i](p.png \"t\")\n```\n[d](z.md)\n```\n");
  EXPECT_EQ(found, (std::vector<std::string>{"docs/x.md", "p.png"}));
}

// Standard output and error of a shell command.
std::string shell(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    ::pclose(pipe);
  }
  return out;
}

std::string run(const std::string& args) { return shell(std::string(CONTACT2D_EXE) + " " + args); }

// Option names ("--dt", "-o") at the start of a help line.
std::set<std::string> options_in_help(const std::string& help) {
  std::set<std::string> out;
  const std::regex option(R"(^\s+(-[A-Za-z0-9],)?(--[a-z0-9][a-z0-9-]*))");
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, option)) out.insert(m[2]);
  }
  return out;
}

std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> out;
  const size_t at = help.find("Subcommands:");
  if (at == std::string::npos) return out;
  std::istringstream lines(help.substr(at));
  const std::regex name(R"(^  ([a-z]+)\s)");
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_search(line, m, name)) out.push_back(m[1]);
  }
  return out;
}

TEST(Docs, CliPageNamesEveryOptionOfEveryCommand) {
  const std::string cli = read_file(kRoot / "docs" / "cli.md");
  const std::string top = run("--help");
  const std::vector<std::string> commands = subcommands(top);
  ASSERT_GE(commands.size(), 5u) << top;
  for (const std::string& option : options_in_help(top))
    EXPECT_NE(cli.find("`" + option), std::string::npos) << "contact2d " << option;
  for (const std::string& command : commands) {
    EXPECT_NE(cli.find("contact2d " + command), std::string::npos) << command;
    const std::set<std::string> options = options_in_help(run(command + " --help"));
    EXPECT_FALSE(options.empty()) << command;
    // Each option appears in the command's own section, which starts at its
    // heading "## contact2d COMMAND".
    const size_t from = cli.find("## contact2d " + command);
    ASSERT_NE(from, std::string::npos) << "no section for " << command;
    const size_t to = cli.find("\n## ", from + 1);
    const std::string section = cli.substr(from, to == std::string::npos ? to : to - from);
    for (const std::string& option : options)
      EXPECT_NE(section.find("`" + option), std::string::npos) << command << " " << option;
  }
}

}  // namespace

namespace {

// The README's tour shows real output: every ```console block's
// "$ build/contact2d …" command is run as from the repository root and each
// line shown under it (but "…") must be a line of what it prints, with the
// wall-clock figure of `simulate`'s summary ("in 1.96 ms") matched as any
// number. "As from the root": in a private folder holding a link to each of
// the root's entries, so that what a command writes (generate -o box.xml)
// lands there, not in the repository.
TEST(Docs, ReadmeTourOutputIsWhatTheProgramPrints) {
  const fs::path here =
      fs::temp_directory_path() / ("contact2d_docs_tour_" + std::to_string(::getpid()));
  fs::create_directories(here);
  for (const fs::directory_entry& entry : fs::directory_iterator(kRoot))
    fs::create_symlink(entry.path(), here / entry.path().filename());
  const std::string readme = read_file(kRoot / "README.md");
  std::istringstream lines(readme);
  bool console = false;
  std::string command;
  std::vector<std::pair<std::string, std::vector<std::string>>> shown;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("```", 0) == 0) {
      console = line == "```console";
      continue;
    }
    if (!console) continue;
    if (line.rfind("$ ", 0) == 0) {
      shown.emplace_back(line.substr(2), std::vector<std::string>{});
    } else if (!shown.empty() && line != "…") {
      shown.back().second.push_back(line);
    }
  }
  int checked = 0;
  const std::regex wall_clock(R"(in [0-9.e+-]+ ms)");
  for (const auto& [cmd, expected] : shown) {
    if (expected.empty() || cmd.rfind("build/contact2d ", 0) != 0) continue;
    const std::string out = shell("cd '" + here.string() + "' && '" + CONTACT2D_EXE + "'" +
                                  cmd.substr(std::string("build/contact2d").size()));
    std::set<std::string> printed;
    std::istringstream out_lines(out);
    for (std::string l; std::getline(out_lines, l);)
      printed.insert(std::regex_replace(l, wall_clock, "in … ms"));
    for (const std::string& line : expected) {
      EXPECT_TRUE(printed.count(std::regex_replace(line, wall_clock, "in … ms")))
          << "the README shows a line that `" << cmd << "` does not print:\n  " << line
          << "\nit printed:\n"
          << out;
      ++checked;
    }
  }
  EXPECT_GE(checked, 5);  // the tour was found at all
  fs::remove_all(here);   // the links, not what they point at
}

}  // namespace
