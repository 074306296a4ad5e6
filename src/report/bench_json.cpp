// Google Benchmark JSON to report::Bench (report/bench_json.hpp).
#include "report/bench_json.hpp"

#include <cctype>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <vector>

namespace contact2d::report {
namespace {

// Just enough of a JSON value: objects keep their members, arrays their
// items, scalars their text (strings unescaped).
struct Value {
  enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
  std::string text;
  double number = 0.0;
  std::vector<Value> items;
  std::vector<std::pair<std::string, Value>> members;

  const Value* get(const std::string& key) const {
    for (const auto& [name, value] : members) {
      if (name == key) return &value;
    }
    return nullptr;
  }
};

class Parser {
 public:
  explicit Parser(const std::string& text) : s_(text) {}

  Value document() {
    Value v = value();
    space();
    if (i_ != s_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("benchmark JSON, offset " + std::to_string(i_) + ": " + why);
  }
  void space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "'");
  }

  std::string string() {
    expect('"');
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      char c = s_[i_++];
      if (c == '\\') {
        if (i_ >= s_.size()) break;
        const char e = s_[i_++];
        switch (e) {
          case 'n': c = '\n'; break;
          case 't': c = '\t'; break;
          case 'r': c = '\r'; break;
          case 'b': c = '\b'; break;
          case 'f': c = '\f'; break;
          case 'u':  // not needed for the fields read: kept as '?'
            if (i_ + 4 > s_.size()) fail("short \\u escape");
            i_ += 4;
            c = '?';
            break;
          default: c = e;
        }
      }
      out += c;
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return out;
  }

  Value value() {
    space();
    if (i_ >= s_.size()) fail("unexpected end");
    Value v;
    const char c = s_[i_];
    if (c == '{') {
      v.kind = Value::Kind::Object;
      ++i_;
      if (eat('}')) return v;
      do {
        space();
        std::string key = string();
        expect(':');
        v.members.emplace_back(std::move(key), value());
      } while (eat(','));
      expect('}');
    } else if (c == '[') {
      v.kind = Value::Kind::Array;
      ++i_;
      if (eat(']')) return v;
      do {
        v.items.push_back(value());
      } while (eat(','));
      expect(']');
    } else if (c == '"') {
      v.kind = Value::Kind::String;
      v.text = string();
    } else if (s_.compare(i_, 4, "true") == 0 || s_.compare(i_, 5, "false") == 0) {
      v.kind = Value::Kind::Bool;
      v.text = s_[i_] == 't' ? "true" : "false";
      i_ += v.text.size();
    } else if (s_.compare(i_, 4, "null") == 0) {
      i_ += 4;
    } else {
      const char* begin = s_.c_str() + i_;
      char* end = nullptr;
      v.number = std::strtod(begin, &end);
      if (end == begin) fail("not a JSON value");
      v.kind = Value::Kind::Number;
      v.text.assign(begin, static_cast<size_t>(end - begin));
      i_ += static_cast<size_t>(end - begin);
    }
    return v;
  }

  const std::string& s_;
  size_t i_ = 0;
};

double to_ns(double value, const std::string& unit) {
  if (unit == "ns") return value;
  if (unit == "us") return value * 1e3;
  if (unit == "ms") return value * 1e6;
  if (unit == "s") return value * 1e9;
  throw std::runtime_error("benchmark JSON: unknown time_unit \"" + unit + "\"");
}

struct Times {
  double cpu_ns = 0.0, real_ns = 0.0;
};

}  // namespace

Bench parse_bench_json(const std::string& json) {
  const Value doc = Parser(json).document();
  const Value* list = doc.get("benchmarks");
  if (doc.kind != Value::Kind::Object || !list || list->kind != Value::Kind::Array) {
    throw std::runtime_error("benchmark JSON: no \"benchmarks\" array");
  }
  std::vector<std::string> ref_order;  // "SCENE/INTEGRATOR" of the reference runs
  std::map<std::string, Times> times;  // by benchmark name
  for (const Value& b : list->items) {
    const Value* name = b.get("name");
    const Value* cpu = b.get("cpu_time");
    const Value* real = b.get("real_time");
    const Value* unit = b.get("time_unit");
    const Value* error = b.get("error_occurred");
    const Value* run_type = b.get("run_type");
    if (!name || !cpu || !real || !unit) continue;  // an error run has no times
    if (error && error->text == "true") continue;
    if (run_type && run_type->text != "iteration") continue;  // aggregates
    times[name->text] = {to_ns(cpu->number, unit->text), to_ns(real->number, unit->text)};
    if (name->text.rfind("ref/", 0) == 0) ref_order.push_back(name->text.substr(4));
  }
  Bench bench;
  bench.ran = true;
  for (const std::string& c : ref_order) {
    const size_t slash = c.find('/');
    BenchRow row;
    row.scene = c.substr(0, slash);
    row.integrator = slash == std::string::npos ? "" : c.substr(slash + 1);
    row.ref_cpu_ns = times["ref/" + c].cpu_ns;
    row.ref_real_ns = times["ref/" + c].real_ns;
    const auto mj = times.find("mj_step/" + c);
    if (mj != times.end()) {
      row.mj_cpu_ns = mj->second.cpu_ns;
      row.mj_real_ns = mj->second.real_ns;
    }
    bench.rows.push_back(row);
  }
  auto floor = [&](const char* name) {
    const auto it = times.find(std::string("floor/") + name);
    return it == times.end() ? -1.0 : it->second.cpu_ns;
  };
  bench.sincos_ns = floor("libm_sincos");
  bench.tanh_ns = floor("libm_tanh");
  bench.free_flight_ns = floor("step_free_flight");
  return bench;
}

}  // namespace contact2d::report
