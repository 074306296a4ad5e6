#include "io/recording.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/format.hpp"
#include "core/input_error.hpp"
#include "io/read_file.hpp"
#include "io/toml_table.hpp"

namespace contact2d {

namespace {

// The CSV split into a header and rows of fields, each row with its line.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> lines;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) {
    while (!field.empty() && (field.back() == '\r' || field.back() == ' ')) field.pop_back();
    while (!field.empty() && field.front() == ' ') field.erase(field.begin());
    fields.push_back(field);
  }
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

Csv read_csv(const std::string& path, const std::string& what) {
  const std::string text = read_input_file(
      path, what, kMaxRecordingBytes, "larger than 64 MiB: split the recording into several files");
  Csv csv;
  // A byte order mark (spreadsheets write one) is not part of the first
  // column's name.
  std::istringstream in(text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? text.substr(3) : text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (csv.header.empty()) {
      csv.header = split(line);
      // A column named twice would be read from its first copy only.
      for (size_t i = 0; i < csv.header.size(); ++i)
        for (size_t j = i + 1; j < csv.header.size(); ++j)
          if (csv.header[i] == csv.header[j] && !csv.header[i].empty())
            throw InputError(path + ":" + std::to_string(number) + ": column '" + csv.header[i] +
                             "' is named twice (columns " + std::to_string(i + 1) + " and " +
                             std::to_string(j + 1) + "): each column once");
      continue;
    }
    std::vector<std::string> fields = split(line);
    if (fields.size() != csv.header.size())
      throw InputError(path + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) +
                       " fields, the header has " + std::to_string(csv.header.size()));
    csv.rows.push_back(std::move(fields));
    csv.lines.push_back(number);
  }
  if (csv.header.empty()) throw InputError(path + ": empty file (no header, no rows)");
  if (csv.rows.empty()) throw InputError(path + ": no rows after the header (an empty recording)");
  return csv;
}

// Column indices of `names` in the header; a missing one is an error that
// lists what the kind needs.
std::vector<size_t> columns(const Csv& csv, const std::vector<std::string>& names,
                            const std::string& path) {
  std::vector<size_t> out;
  std::string all;
  for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
  for (const std::string& n : names) {
    size_t i = 0;
    while (i < csv.header.size() && csv.header[i] != n) ++i;
    if (i == csv.header.size()) {
      std::string found;
      for (const std::string& h : csv.header) found += (found.empty() ? "'" : "', '") + h;
      throw InputError(path + ": missing column '" + n + "' (the columns are " + all +
                       "; the header has " + found + "')");
    }
    out.push_back(i);
  }
  return out;
}

double number(const Csv& csv, size_t row, size_t column, const std::string& path) {
  const std::string& text = csv.rows[row][column];
  const std::string where =
      path + ":" + std::to_string(csv.lines[row]) + ": field '" + csv.header[column] + "'";
  if (text.empty()) throw InputError(where + " is empty: it must be a finite number");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  // Decimal text only: strtod also reads hexadecimal (0x1p-2).
  if (end != text.c_str() + text.size() || text.find_first_of("xX") != std::string::npos)
    throw InputError(where + " = '" + text + "' is not a decimal number");
  if (!std::isfinite(v)) throw InputError(where + " = " + text + ": it must be a finite number");
  return v;
}

int integer(const Csv& csv, size_t row, size_t column, const std::string& path) {
  const double v = number(csv, row, column, path);
  if (v != std::floor(v) || std::abs(v) > 1e9)
    throw InputError(path + ":" + std::to_string(csv.lines[row]) + ": field '" +
                     csv.header[column] + "' = " + csv.rows[row][column] +
                     ": it must be an integer id in [-1e9, 1e9]");
  return static_cast<int>(v);
}

State state_at(const Csv& csv, size_t row, const std::vector<size_t>& col, size_t first,
               const std::string& path) {
  State s;
  s.q = Vec3(number(csv, row, col[first], path), number(csv, row, col[first + 1], path),
             number(csv, row, col[first + 2], path));
  s.v = Vec3(number(csv, row, col[first + 3], path), number(csv, row, col[first + 4], path),
             number(csv, row, col[first + 5], path));
  return s;
}

// `velocities`: whether vx, vy, omega are required (the recording's own
// trajectories); a peer's file may leave all three out (then they are 0 and
// RecordedTrajectory::velocities is false), or give all three.
std::vector<RecordedTrajectory> read_trajectories(const std::string& path, bool velocities) {
  const Csv csv = read_csv(path, "trajectories");
  const auto has = [&csv](const char* name) {
    return std::find(csv.header.begin(), csv.header.end(), name) != csv.header.end();
  };
  if (!velocities) velocities = has("vx") || has("vy") || has("omega");
  std::vector<std::string> names = {"traj", "t", "x", "y", "theta"};
  if (velocities) names.insert(names.end(), {"vx", "vy", "omega"});
  const std::vector<size_t> col = columns(csv, names, path);
  std::vector<RecordedTrajectory> out;
  std::map<int, size_t> seen;
  for (size_t r = 0; r < csv.rows.size(); ++r) {
    const int id = integer(csv, r, col[0], path);
    const double t = number(csv, r, col[1], path);
    if (out.empty() || out.back().id != id) {
      if (seen.count(id))
        throw InputError(path + ":" + std::to_string(csv.lines[r]) +
                         ": field 'traj' = " + std::to_string(id) +
                         ": this trajectory's rows must be consecutive (it appeared before, "
                         "at line " +
                         std::to_string(out[seen[id]].line) + ")");
      seen[id] = out.size();
      out.push_back({id, csv.lines[r], velocities, {}, {}, {}});
    } else if (!(t > out.back().t.back())) {
      throw InputError(path + ":" + std::to_string(csv.lines[r]) +
                       ": field 't' = " + format_shortest(t) + " is not after the row before's " +
                       format_shortest(out.back().t.back()) +
                       " (time must increase within a trajectory)");
    }
    out.back().lines.push_back(csv.lines[r]);
    out.back().t.push_back(t);
    State s;
    if (velocities) {
      s = state_at(csv, r, col, 2, path);
    } else {
      s.q = Vec3(number(csv, r, col[2], path), number(csv, r, col[3], path),
                 number(csv, r, col[4], path));
      s.v = Vec3::Zero();
    }
    out.back().states.push_back(s);
  }
  return out;
}

}  // namespace

Recording read_recording(const std::string& path) {
  const std::string text = read_input_file(path, "recording manifest");
  const toml::table root = parse_toml(text, path);
  Recording rec;
  rec.path = path;
  TableReader top(&root, "", path);
  top.string("kind", rec.kind);
  if (rec.kind != "impacts" && rec.kind != "trajectories")
    top.fail("kind", rec.kind.empty()
                         ? "is required: \"impacts\" or \"trajectories\""
                         : "= \"" + rec.kind + "\": use \"impacts\" or \"trajectories\"");
  std::string csv_name, peer_csv;
  top.string("csv", csv_name);
  if (csv_name.empty()) top.fail("csv", "is required: the data file, relative to this file");
  top.string("peer_csv", peer_csv);
  top.string("peer", rec.peer);
  double gravity = 9.81;
  top.number("gravity", gravity);
  if (!(gravity > 0.0 && gravity <= 1e3)) top.fail("gravity", "must be in (0, 1e3] m/s²");
  top.number("frame_rate", rec.frame_rate);
  if (!(rec.frame_rate > 0.0 && rec.frame_rate <= 1e7))
    top.fail("frame_rate", "is required, in (0, 1e7] Hz: the camera's rate");
  const toml::node* source = root.get("source");
  if (source && source->is_table()) {
    TableReader src(source->as_table(), "source.", path);
    src.string("citation", rec.citation);
    src.string("licence", rec.licence);
  }
  top.mark_used("source");
  top.mark_used("body");
  top.reject_unknown("kind, csv, peer_csv, peer, gravity, frame_rate, [body], [source]");

  const toml::node* body = root.get("body");
  if (!body || !body->is_table())
    throw InputError(path + ": [body] is required: shape and its dimensions, mass");
  toml::table body_table = *body->as_table();
  std::string shape_text;
  TableReader(&body_table, "body.", path).string("shape", shape_text);
  const std::optional<Shape> shape = parse_shape(shape_text);
  if (!shape)
    throw InputError(path + ": body.shape = \"" + shape_text +
                     "\": use point_mass, box, tshape, circle or ellipse");
  body_table.erase("shape");
  // A recorded body has no defaults: a scene file's (a 0.2 × 0.1 m ellipse,
  // 1 kg) would silently stand in for a measurement left out.
  std::vector<const char*> required = {"mass"};
  switch (*shape) {
    case Shape::PointMass: break;
    case Shape::Box: required.insert(required.end(), {"width", "height"}); break;
    case Shape::TShape: required = {"parts"}; break;
    case Shape::Circle: required.push_back("radius"); break;
    case Shape::Ellipse: required.insert(required.end(), {"a", "b"}); break;
  }
  for (const char* key : required) {
    if (!body_table.contains(key))
      throw InputError(path + ": body." + key + " is required for a recorded " + shape_text +
                       " (a recording takes no default dimensions or mass)");
  }
  rec.body = default_scene(*shape);
  rec.body.sim.gravity = gravity;
  read_body(&body_table, rec.body, path);
  if (const auto error = validate(rec.body))
    throw InputError(path + ": " + error->key + " " + error->range);

  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  rec.csv = (dir / csv_name).string();
  if (rec.kind == "trajectories") {
    rec.trajectories = read_trajectories(rec.csv, true);
    if (!peer_csv.empty()) {
      rec.peer_csv = (dir / peer_csv).string();
      rec.peer_trajectories = read_trajectories(rec.peer_csv, false);
    }
    return rec;
  }
  const Csv csv = read_csv(rec.csv, "impacts");
  const std::vector<size_t> col = columns(csv,
                                          {"impact", "x0", "y0", "theta0", "vx0", "vy0", "omega0",
                                           "x1", "y1", "theta1", "vx1", "vy1", "omega1"},
                                          rec.csv);
  size_t flags = csv.header.size();
  for (size_t i = 0; i < csv.header.size(); ++i)
    if (csv.header[i] == "flags") flags = i;
  std::map<int, int> line_of;  // each impact's id, to refuse one named twice
  for (size_t r = 0; r < csv.rows.size(); ++r) {
    RecordedImpact impact;
    impact.id = integer(csv, r, col[0], rec.csv);
    impact.line = csv.lines[r];
    const auto [earlier, fresh] = line_of.emplace(impact.id, impact.line);
    if (!fresh)
      throw InputError(rec.csv + ":" + std::to_string(impact.line) + ": impact " +
                       std::to_string(impact.id) + " again (first on line " +
                       std::to_string(earlier->second) + "): each impact's id is unique");
    impact.before = state_at(csv, r, col, 1, rec.csv);
    impact.after = state_at(csv, r, col, 7, rec.csv);
    if (flags < csv.header.size()) {
      impact.flags = csv.rows[r][flags];
      if (impact.flags.find_first_not_of("01") != std::string::npos)
        throw InputError(rec.csv + ":" + std::to_string(impact.line) + ": field 'flags' = '" +
                         impact.flags +
                         "': it must be a string of 0s and 1s (all 0: a clean impact)");
    }
    rec.impacts.push_back(impact);
  }
  return rec;
}

}  // namespace contact2d
