// _contact2d: the compiled half of the Python module `contact2d`
// (src/python/contact2d/__init__.py is the other half; docs/python.md).
//
// A thin layer over the libraries the program calls, so the numbers are
// the program's to the bit: a scene is the core's Scene struct itself,
// simulate runs engines::run_engine, compare the comparison of
// analysis/compare_run.hpp and its --json text, generate the MJCF writer,
// solref mujoco/solref_request.hpp and inspect mujoco/inspect.hpp with
// their --json texts. What the program prints as JSON reaches Python as
// that same text (the Python half parses it), so a dict holds exactly the
// numbers `--json` prints; trajectories cross as numpy arrays of the
// engines' doubles.
//
// Errors become Python exceptions with the program's one-line message:
// InputError (bad input) → ValueError, a file that does not exist →
// FileNotFoundError, a divergence or a run that is not physics →
// RuntimeError. The engines run on a worker thread with the GIL released,
// and Ctrl-C stops them with KeyboardInterrupt (python/interruptible.hpp).
//
// Enumerations cross as their names (the scene file's words: "box",
// "kelvin_voigt", "rk4"), through the core's name and parse functions.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/compare_run.hpp"
#include "analysis/real_impacts.hpp"
#include "analysis/tables.hpp"
#include "core/cancel.hpp"
#include "core/format.hpp"
#include "core/input_error.hpp"
#include "core/scene.hpp"
#include "engines/engines.hpp"
#include "io/recording.hpp"
#include "io/scene_file.hpp"
#include "mujoco/inspect.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/solref_request.hpp"
#include "mujoco3/inspect_versions.hpp"
#include "mujoco3/own_model.hpp"
#include "python/interruptible.hpp"

namespace py = pybind11;
using namespace contact2d;

namespace {

// A file named by the caller that does not exist: FileNotFoundError.
struct FileMissing : InputError {
  using InputError::InputError;
};
// A run that diverged or is not physics: RuntimeError.
struct RunFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `f`; an InputError while `path` does not exist becomes FileMissing
// with the same message (the program's line for that file).
template <typename F>
auto reading(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    std::error_code ec;
    if (!path.empty() && !std::filesystem::exists(path, ec)) throw FileMissing(e.what());
    throw;
  }
}

// The scene file's words for the enumerations; a bad word is the scene
// reader's message for that key.
std::string damping_name(DampingLaw law) { return std::string(damping_law_name(law)); }
DampingLaw parse_damping(const std::string& name) {
  if (const auto law = parse_damping_law(name)) return *law;
  throw InputError("contact.damping = \"" + name +
                   "\" is not a damping law: use \"compression\" or \"kelvin_voigt\"");
}
FrictionLaw parse_friction(const std::string& name) {
  if (const auto law = parse_friction_law(name)) return *law;
  throw InputError("contact.friction_law = \"" + name +
                   "\" is not a friction law: use \"tanh\", \"viscous_cone\" or \"soft_cone\"");
}
Integrator parse_integrator_or_throw(const std::string& name) {
  if (const auto i = parse_integrator(name)) return *i;
  throw InputError("sim.integrator = \"" + name +
                   "\" is not an integrator: use explicit_euler, semi_implicit_euler, "
                   "implicit_euler or rk4");
}
Shape parse_shape_or_throw(const std::string& name) {
  if (const auto s = parse_shape(name)) return *s;
  throw InputError("scene = \"" + name +
                   "\" is not a scene: use point_mass, box, tshape, circle or ellipse");
}

// The scene file of a scene, as given to Scene.load ("" when built in Python).
std::string source_of(const py::object& scene) {
  return py::hasattr(scene, "source") ? py::str(scene.attr("source")).cast<std::string>() : "";
}

// A copy of the scene with the run's overrides, checked as the scene reader
// checks a file ("FILE: key = value is out of range: range").
Scene checked_scene(const py::object& object, const std::optional<std::string>& integrator,
                    std::optional<double> dt, std::optional<double> duration) {
  Scene scene = object.cast<Scene>();
  if (integrator) scene.sim.integrator = parse_integrator_or_throw(*integrator);
  if (dt) scene.sim.dt = *dt;
  if (duration) scene.sim.duration = *duration;
  if (const auto error = validate(scene)) {
    const std::string source = source_of(object);
    throw InputError((source.empty() ? std::string("scene") : source) + ": " + error->key + " = " +
                     format_number("%g", error->value) + " is out of range: " + error->range);
  }
  return scene;
}

py::array_t<double> trajectory_array(const Trajectory& t) {
  py::array_t<double> a({static_cast<py::ssize_t>(t.samples.size()), py::ssize_t{7}});
  auto m = a.mutable_unchecked<2>();
  for (size_t i = 0; i < t.samples.size(); ++i) {
    const Sample& s = t.samples[i];
    const auto r = static_cast<py::ssize_t>(i);
    m(r, 0) = s.t;
    for (int j = 0; j < 3; ++j) {
      m(r, 1 + j) = s.state.q[j];
      m(r, 4 + j) = s.state.v[j];
    }
  }
  return a;
}

// The converged solution at the samples of `at` (compare's CSV columns).
py::array_t<double> converged_array(const DenseTrajectory& d, const Trajectory& at) {
  Trajectory t;
  for (const Sample& s : at.samples) t.samples.push_back({s.t, d.at(s.t)});
  return trajectory_array(t);
}

// model_dt as the CLI's --model-dt takes it: (0, 1] s, or not given (None).
double checked_model_dt(const std::optional<double>& model_dt) {
  if (!model_dt) return 0.0;
  if (!(*model_dt > 0.0 && *model_dt <= 1.0))
    throw InputError("model_dt = " + format_number("%g", *model_dt) +
                     " is out of range: must be in (0, 1] s (or None: the timestep)");
  return *model_dt;
}

// How a Python caller wrote an option, to start an error: "mapping =".
std::string python_keyword(std::string_view name) { return std::string(name) + " ="; }

// A kept run that is not physics: the program's line, with the keyword
// that keeps it in Python's terms.
std::string not_physics(const std::string& source, const std::string& engine,
                        const std::string& reason, bool kept) {
  const std::string who = source + ": " + (engine.empty() ? "" : engine + " ");
  return kept ? who + "warning: not physics, kept (allow_nonphysical=True): " + reason
              : who + "not physics: " + reason + ". Pass allow_nonphysical=True to keep the run.";
}

py::dict py_simulate(const py::object& scene_object, const std::string& engine,
                     const std::optional<std::string>& integrator, std::optional<double> dt,
                     std::optional<double> duration, const std::string& mapping,
                     const std::string& geometry, const std::string& friction,
                     const std::optional<double>& model_dt_given, bool allow_nonphysical) {
  const double model_dt = checked_model_dt(model_dt_given);
  const Scene scene = checked_scene(scene_object, integrator, dt, duration);
  const std::string source = source_of(scene_object);
  const engines::EngineSpec spec = engines::engine_with_options(
      engine, {{"mapping", mapping}, {"geometry", geometry}, {"friction", friction}}, model_dt,
      source, python_keyword);
  const engines::EngineRun run =
      python::interruptible([&] { return engines::run_engine(spec, scene); });
  if (run.trajectory.divergence) throw RunFailed(source + ": " + run.divergence_message);
  std::vector<std::string> warnings = run.warnings;
  if (const std::string reason = nonphysical(run.trajectory, scene); !reason.empty()) {
    if (!allow_nonphysical) throw RunFailed(not_physics(source, "", reason, false));
    warnings.push_back(not_physics(source, "", reason, true));
  }
  py::dict out;
  out["trajectory"] = trajectory_array(run.trajectory);
  out["warnings"] = warnings;
  out["notes"] = run.notes;
  out["engine"] = run.engine;
  out["description"] = run.description;
  out["seconds"] = run.seconds;
  out["summary"] = analysis::run_summary(scene, engine, run);
  return out;
}

py::dict py_compare(const py::object& scene_object, const std::optional<std::string>& integrator,
                    std::optional<double> dt, std::optional<double> duration,
                    const std::string& mapping, const std::string& geometry,
                    const std::string& friction, const std::optional<double>& model_dt_given,
                    const std::vector<std::string>& engine_names, double converged_tol,
                    bool diagnosis, bool full_diagnosis, bool allow_nonphysical) {
  const double model_dt = checked_model_dt(model_dt_given);
  const std::string source = source_of(scene_object);
  if (!(converged_tol >= 1e-14 && converged_tol <= 1e-6))
    throw InputError("converged_tol = " + format_number("%g", converged_tol) +
                     " is out of range: must be in [1e-14, 1e-6]");
  analysis::Comparison c = analysis::prepare_comparison(
      checked_scene(scene_object, integrator, dt, duration),
      analysis::comparison_engines(
          engine_names, {{"mapping", mapping}, {"geometry", geometry}, {"friction", friction}},
          model_dt, source, python_keyword));
  std::vector<std::string> warnings;
  python::interruptible([&] {
    analysis::run_engines(c, diagnosis);
    return true;
  });
  for (const analysis::ComparedRun& r : c.runs)
    for (const std::string& w : r.run.warnings) warnings.push_back(r.label + " warning: " + w);
  for (const analysis::RunProblem& p : analysis::run_problems(c)) {
    if (p.diverged) throw RunFailed(source + ": " + p.engine + ": " + p.message);
    if (!allow_nonphysical) throw RunFailed(not_physics(source, p.engine, p.message, false));
    warnings.push_back(not_physics(source, p.engine, p.message, true));
  }
  python::interruptible([&] {
    analysis::DiagnosisOptions how;
    how.full = full_diagnosis;
    analysis::measure(c, converged_tol, diagnosis, how);
    return true;
  });
  py::dict out;
  out["json"] = analysis::comparison_json(c, source);
  out["text"] = analysis::comparison_text(c);  // what `contact2d compare` prints
  for (const analysis::ComparedRun& r : c.runs)
    out[(r.key + "_trajectory").c_str()] = trajectory_array(r.run.trajectory);
  out["converged_trajectory"] =
      c.converged.available
          ? py::object(converged_array(c.converged.trajectory, c.runs[0].run.trajectory))
          : py::object(py::none());
  out["warnings"] = warnings;
  return out;
}

py::dict py_generate(const py::object& scene_object, const std::optional<std::string>& integrator,
                     std::optional<double> dt, std::optional<double> duration,
                     const std::string& mapping, const std::string& geometry,
                     const std::string& friction, const std::string& engine,
                     const std::optional<double>& model_dt_given) {
  const double model_dt = checked_model_dt(model_dt_given);
  const Scene scene = checked_scene(scene_object, integrator, dt, duration);
  mujoco::MjcfOptions options = mujoco::mjcf_options(mapping, geometry, source_of(scene_object));
  options.model_dt = model_dt;
  if (engine != "mujoco" && engine != "mujoco3")
    throw InputError("engine = " + engine + ": generate writes for mujoco (2.2.2) or mujoco3");
  if (!friction.empty() && friction != "shared" && friction != "damper")
    throw InputError("friction = " + friction + ": unknown (shared, damper)");
  options.friction_damper = friction == "damper";
  if (engine == "mujoco3") options.version = mujoco::Version::V3;
  const mujoco::GeneratedModel model =
      python::interruptible([&] { return mujoco::generate_mjcf(scene, options); });
  std::vector<std::string> notes;
  if (model.settings.refsafe_clamped)
    notes.push_back("timeconst " + format_number(model.settings.solref[0]) +
                    " s < 2 dt: MuJoCo raises it to 2 dt (refsafe), a softer contact than "
                    "contact.k");
  py::dict out;
  out["xml"] = model.xml;
  out["notes"] = notes;
  return out;
}

py::dict py_solref(const mujoco::SolrefRequest& request) {
  std::vector<std::string> notes;
  const mujoco::SolrefReport report = python::interruptible([&] {
    return reading(request.model, [&] {
      return mujoco3::solref(request, [&notes](const std::string& line) { notes.push_back(line); });
    });
  });
  if (!report.apply_refused.empty()) throw InputError(report.apply_refused);
  py::dict out;
  out["json"] = mujoco::format_report_json(report);
  out["notes"] = notes;
  return out;
}

// contact2d fit on a recording: the JSON the program prints, and per model
// the held-out impacts' ids, errors, predicted and measured velocities.
py::dict py_fit(const std::string& path, long long seed, int bootstrap,
                std::optional<std::vector<std::string>> engines, unsigned threads, bool all_impacts,
                bool k_profile) {
  analysis::ImpactFitOptions options;
  options.seed = static_cast<std::uint64_t>(seed);
  options.bootstrap = bootstrap;
  options.engines = engines ? *engines : analysis::default_fit_engines();
  options.threads = threads;
  options.all_impacts = all_impacts;
  options.k_profile = k_profile;
  const analysis::ImpactFit fit = python::interruptible([&] {
    return reading(path, [&] {
      const Recording rec = read_recording(path);
      if (rec.kind != "impacts")
        throw InputError(path + ": kind = \"" + rec.kind +
                         "\": fit() takes \"impacts\" recordings (trajectories are not fitted "
                         "yet)");
      return analysis::fit_impacts(rec, options);
    });
  });
  py::list models;
  for (const analysis::SplitFit& split : fit.splits) {
    for (const analysis::ModelFit& m : split.models) {
      const auto n = static_cast<py::ssize_t>(split.test.size());
      py::array_t<long long> ids(n);
      py::array_t<double> errors(n);
      py::array_t<double> predicted({n, py::ssize_t{3}});
      py::array_t<double> measured({n, py::ssize_t{3}});
      auto id = ids.mutable_unchecked<1>();
      auto e = errors.mutable_unchecked<1>();
      auto p = predicted.mutable_unchecked<2>();
      auto v = measured.mutable_unchecked<2>();
      for (py::ssize_t i = 0; i < n; ++i) {
        const RecordedImpact& impact = fit.impacts[split.test[static_cast<size_t>(i)]];
        id(i) = impact.id;
        e(i) = m.errors[static_cast<size_t>(i)];
        for (py::ssize_t j = 0; j < 3; ++j) {
          p(i, j) = m.predicted[static_cast<size_t>(i)][j];
          v(i, j) = impact.after.v[j];
        }
      }
      py::dict entry;
      entry["name"] = m.name;
      entry["engine"] = m.engine;
      entry["split"] = m.split;
      entry["impacts"] = ids;
      entry["errors"] = errors;
      entry["predicted"] = predicted;
      entry["measured"] = measured;
      models.append(entry);
    }
  }
  py::dict out;
  out["json"] = analysis::impact_fit_json(fit);
  out["arrays"] = models;
  return out;
}

py::dict py_inspect(const std::string& path, const std::string& key, bool pairs,
                    std::optional<double> slope, double settle, bool estimate_loads,
                    const std::string& engine, bool rest_search) {
  mujoco::InspectOptions options;
  options.path = path;
  options.key = key;
  options.pairs = pairs;
  options.slope = slope;
  options.settle = settle;
  options.estimate_loads = estimate_loads;
  // As the program: when the model is not at rest, how long it takes to be.
  const mujoco::InspectReport report = python::interruptible([&] {
    return reading(path, [&] {
      mujoco::InspectReport r = mujoco3::inspect(options, engine);
      if (rest_search) mujoco3::settle_time(r, options, engine);
      return r;
    });
  });
  std::vector<std::string> notes;
  if (!report.load_warning.empty())
    notes.push_back("MuJoCo warns while loading " + path + ": " + report.load_warning);
  py::dict out;
  out["json"] = mujoco::format_inspect_json(report);
  out["notes"] = notes;
  return out;
}

// A copy that keeps the scene file it came from.
py::object copy_scene(const py::object& self) {
  py::object copy = py::cast(self.cast<Scene>());
  if (py::hasattr(self, "source")) copy.attr("source") = self.attr("source");
  return copy;
}

// Scene.load(path, set): the path as str or os.PathLike.
py::object load(const py::object& given, const std::vector<std::string>& sets) {
  if (!py::isinstance<py::str>(given) &&
      !py::isinstance(given, py::module_::import("os").attr("PathLike")))
    throw py::type_error("Scene.load(): path must be a path (str or os.PathLike), not " +
                         py::str(py::type::of(given).attr("__name__")).cast<std::string>());
  const std::string path = py::module_::import("os").attr("fspath")(given).cast<std::string>();
  // The C library stops a path at a NUL: 'box.toml\x00junk' opened box.toml.
  if (path.find('\0') != std::string::npos)
    throw py::value_error("Scene.load(): path has a NUL character, which no file name can hold");
  std::vector<Override> overrides;
  overrides.reserve(sets.size());
  for (const std::string& s : sets) overrides.push_back(parse_override(s));
  py::object object = py::cast(reading(path, [&] { return load_scene(path, overrides); }));
  object.attr("source") = path;
  return object;
}

// Python exceptions for the program's errors (the header says which).
void bind_exceptions() {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const FileMissing& e) {
      PyErr_SetString(PyExc_FileNotFoundError, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const RunFailed& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    } catch (const Cancelled&) {
      // Another thread's Ctrl-C (interruptible.hpp): contact2d.Cancelled.
      PyErr_SetString(py::module_::import("contact2d").attr("Cancelled").ptr(),
                      "cancelled: Ctrl-C on the main thread ends every contact2d call in progress");
    }
  });
}

// What a wrong type for a field says, as the functions say it for a
// keyword ("simulate(): dt must be a number (s), not str '1e-3'"): the
// scene file's key, what it takes, and the value given. pybind11's own
// text was "(): incompatible function arguments".
[[noreturn]] void wrong_type(const std::string& key, const std::string& wanted,
                             const py::handle& value) {
  throw py::type_error(key + " must be " + wanted + ", not " +
                       py::str(py::type::of(value).attr("__name__")).cast<std::string>() + " " +
                       py::repr(value).cast<std::string>());
}

// A real number (int, float, a numpy scalar; not a bool, not a string) as a
// double, else wrong_type naming `key` and its unit.
double real_number(const py::handle& value, const std::string& key, const std::string& unit) {
  if (!py::isinstance<py::bool_>(value) &&
      py::isinstance(value, py::module_::import("numbers").attr("Real")))
    return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  wrong_type(key, "a number (" + unit + ")", value);
}

// A str, else wrong_type naming `key` and the words it takes.
std::string word(const py::handle& value, const std::string& key, const std::string& words) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  wrong_type(key, "a string, " + words, value);
}

// A number field of a scene part, its setter checked by real_number.
template <typename C>
void number_field(py::class_<C>& cls, const char* name, double C::*member, const std::string& key,
                  const std::string& unit, const std::string& doc) {
  cls.def_property(
      name, [member](const C& c) { return c.*member; },
      [member, key, unit](C& c, const py::object& value) {
        c.*member = real_number(value, key, unit);
      },
      (doc.empty() ? unit : doc + ", " + unit).c_str());
}

// A scene part (Contact, State, Sim) assigned whole, checked for its type.
template <typename T>
py::cpp_function part_setter(T Scene::*member, const std::string& key, const std::string& type) {
  return py::cpp_function([member, key, type](Scene& s, const py::object& value) {
    if (!py::isinstance<T>(value)) wrong_type(key, "a contact2d." + type, value);
    s.*member = value.cast<T>();
  });
}

// The parts of a scene: BoxPart, Contact, State and Sim.
void bind_scene_parts(py::module_& m) {
  py::class_<BoxPart> part(m, "BoxPart", "One rectangle of a tshape's body (body.parts)");
  part.def(py::init([](const py::object& width, const py::object& height, const py::object& x,
                       const py::object& y, const py::object& mass) {
             const std::string key = "BoxPart(): ";
             return BoxPart{real_number(width, key + "width", "m"),
                            real_number(height, key + "height", "m"),
                            real_number(x, key + "x", "m"), real_number(y, key + "y", "m"),
                            real_number(mass, key + "mass", "kg")};
           }),
           py::arg("width"), py::arg("height"), py::arg("x"), py::arg("y"), py::arg("mass"));
  number_field(part, "width", &BoxPart::width, "body.parts[].width", "m", "");
  number_field(part, "height", &BoxPart::height, "body.parts[].height", "m", "");
  number_field(part, "x", &BoxPart::x, "body.parts[].x", "m", "centre x in the body frame");
  number_field(part, "y", &BoxPart::y, "body.parts[].y", "m", "centre y in the body frame");
  number_field(part, "mass", &BoxPart::mass, "body.parts[].mass", "kg", "");

  py::class_<ContactParams> contact(m, "Contact", "[contact]: the contact law (docs/scenes.md)");
  number_field(contact, "k", &ContactParams::k, "contact.k", "N/m", "stiffness");
  number_field(contact, "c", &ContactParams::c, "contact.c", "N·s/m", "damping");
  number_field(contact, "mu", &ContactParams::mu, "contact.mu", "dimensionless",
               "sliding friction coefficient");
  number_field(contact, "alpha", &ContactParams::alpha, "contact.alpha", "s/m",
               "tanh regularisation of friction");
  number_field(contact, "mu_roll", &ContactParams::mu_roll, "contact.mu_roll", "m",
               "rolling resistance");
  number_field(contact, "mu_torsion", &ContactParams::mu_torsion, "contact.mu_torsion", "m",
               "torsional friction (MuJoCo only; 2D has no torsion)");
  number_field(contact, "cone_ratio", &ContactParams::cone_ratio, "contact.cone_ratio",
               "dimensionless", "the cone laws' ratio (MuJoCo's impratio)");
  contact
      .def_property(
          "damping", [](const ContactParams& p) { return damping_name(p.damping); },
          [](ContactParams& p, const py::object& name) {
            p.damping =
                parse_damping(word(name, "contact.damping", "\"compression\" or \"kelvin_voigt\""));
          },
          "\"compression\" (damps only while a point moves in) or \"kelvin_voigt\"")
      .def_property(
          "friction_law",
          [](const ContactParams& p) { return std::string(friction_law_name(p.friction)); },
          [](ContactParams& p, const py::object& name) {
            p.friction = parse_friction(
                word(name, "contact.friction_law", "\"tanh\", \"viscous_cone\" or \"soft_cone\""));
          },
          "\"tanh\", \"viscous_cone\" or \"soft_cone\" (docs/physics.md)");

  // [initial]: q = (x, y, θ), v = (vx, vy, ω), by the scene file's keys.
  py::class_<State> state(m, "State", "[initial]: the initial state (docs/scenes.md)");
  const char* names[] = {"x", "y", "theta", "vx", "vy", "omega"};
  const char* units[] = {"m", "m", "rad", "m/s", "m/s", "rad/s"};
  for (int i = 0; i < 6; ++i) {
    Vec3 State::*vector = i < 3 ? &State::q : &State::v;
    const int j = i % 3;
    const std::string key = std::string("initial.") + names[i];
    const std::string unit = units[i];
    state.def_property(
        names[i], [vector, j](const State& s) { return (s.*vector)[j]; },
        [vector, j, key, unit](State& s, const py::object& value) {
          (s.*vector)[j] = real_number(value, key, unit);
        },
        units[i]);
  }

  py::class_<SimParams> sim(m, "Sim", "[sim]: time stepping (docs/scenes.md)");
  number_field(sim, "dt", &SimParams::dt, "sim.dt", "s", "time step");
  number_field(sim, "duration", &SimParams::duration, "sim.duration", "s", "simulated time");
  number_field(sim, "output_dt", &SimParams::output_dt, "sim.output_dt", "s",
               "sample spacing of the trajectory");
  number_field(sim, "gravity", &SimParams::gravity, "sim.gravity", "m/s²", "");
  sim.def_property(
      "integrator", [](const SimParams& s) { return std::string(integrator_name(s.integrator)); },
      [](SimParams& s, const py::object& name) {
        s.integrator = parse_integrator_or_throw(
            word(name, "sim.integrator",
                 "\"explicit_euler\", \"semi_implicit_euler\", \"implicit_euler\" or \"rk4\""));
      },
      "\"explicit_euler\", \"semi_implicit_euler\", \"implicit_euler\" or \"rk4\"");
}

// Scene.parts = a list of BoxPart, checked item by item.
void set_parts(Scene& s, const py::object& value) {
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value))
    wrong_type("body.parts", "a list of contact2d.BoxPart", value);
  std::vector<BoxPart> parts;
  size_t i = 0;
  for (const py::handle item : value) {
    if (!py::isinstance<BoxPart>(item))
      wrong_type("body.parts[" + std::to_string(i) + "]", "a contact2d.BoxPart", item);
    parts.push_back(item.cast<BoxPart>());
    ++i;
  }
  s.parts = std::move(parts);
}

const char* const kShapes = "\"point_mass\", \"box\", \"tshape\", \"circle\" or \"ellipse\"";

void bind_scene(py::module_& m) {
  py::class_<Scene> scene(m, "Scene", py::dynamic_attr(),
                          "A scene: body, contact, initial state, sim");
  scene
      .def(py::init([](const py::object& shape) {
             return default_scene(parse_shape_or_throw(word(shape, "Scene(): shape", kShapes)));
           }),
           py::arg("shape") = "point_mass")
      .def_static("load", &load, py::arg("path"), py::arg("set") = std::vector<std::string>{},
                  "The scene of a TOML scene file (str or os.PathLike), with overrides "
                  "\"KEY=VALUE\" as --set (docs/scenes.md)")
      .def_property(
          "shape", [](const Scene& s) { return std::string(shape_name(s.shape)); },
          [](Scene& s, const py::object& name) {
            s.shape = parse_shape_or_throw(word(name, "shape", kShapes));
          },
          kShapes);
  number_field(scene, "mass", &Scene::mass, "body.mass", "kg",
               "body mass (not a tshape: its parts carry theirs)");
  number_field(scene, "half_height", &Scene::half_height, "body.half_height", "m",
               "point_mass: the contact point's distance below the centre");
  number_field(scene, "width", &Scene::width, "body.width", "m", "box width");
  number_field(scene, "height", &Scene::height, "body.height", "m", "box height");
  number_field(scene, "radius", &Scene::radius, "body.radius", "m", "circle radius");
  number_field(scene, "a", &Scene::a, "body.a", "m", "ellipse: semi-axis along the body's x");
  number_field(scene, "b", &Scene::b, "body.b", "m", "ellipse: semi-axis along the body's y");
  number_field(scene, "inertia", &Scene::inertia, "body.inertia", "kg·m²",
               "ellipse: inertia about the centre (0: a plate's m·(a² + b²)/4)");
  scene
      .def_property(
          "parts", [](const Scene& s) { return s.parts; }, &set_parts,
          "tshape: the body's rectangles (list of BoxPart)")
      .def_property(
          "contact", [](Scene& s) -> ContactParams& { return s.contact; },
          part_setter(&Scene::contact, "contact", "Contact"), "[contact] (Contact)")
      .def_property(
          "initial", [](Scene& s) -> State& { return s.initial; },
          part_setter(&Scene::initial, "initial", "State"), "[initial]: the initial state (State)")
      .def_property(
          "sim", [](Scene& s) -> SimParams& { return s.sim; },
          part_setter(&Scene::sim, "sim", "Sim"), "[sim] (Sim)")
      .def_property_readonly(
          "obstacles", [](const Scene& s) { return s.obstacles.size(); },
          "the number of obstacles (set in the scene file: [[obstacle]])")
      .def(
          "validate", [](const py::object& self) { checked_scene(self, {}, {}, {}); },
          "Raises ValueError naming the first key out of its range, as the program does")
      .def("copy", &copy_scene, "An independent copy (the scene file it came from kept)")
      .def("__copy__", &copy_scene)
      .def("__deepcopy__",
           [](const py::object& self, const py::dict&) { return copy_scene(self); });
}

// The commands, run by the Python half.
void bind_commands(py::module_& m) {
  m.attr("__version__") = CONTACT2D_VERSION;  // CMake's project(VERSION)
  m.def("_simulate", &py_simulate);
  m.def("_compare", &py_compare);
  m.def("_generate", &py_generate);
  m.def("_inspect", &py_inspect);
  m.def("_fit", &py_fit);
  m.def("_solref",
        [](std::optional<double> k, std::optional<double> c, std::optional<double> dt,
           std::optional<double> mass, const std::string& mapping, std::optional<std::string> joint,
           double inertia, double lever, double pivot, std::optional<double> mu, double mu_roll,
           const std::string& model, const std::string& body, std::optional<int> contacts,
           std::optional<double> restitution, std::optional<double> contact_time,
           std::optional<double> penetration, const std::string& engine, double settle,
           const std::string& key, const std::string& apply, std::optional<double> slope) {
          mujoco::SolrefRequest r;
          r.k = k;
          r.c = c;
          r.dt = dt;
          r.mass = mass;
          r.mapping = mapping;
          r.joint = std::move(joint);
          r.inertia = inertia;
          r.lever = lever;
          r.pivot = pivot;
          r.mu = mu;
          r.mu_roll = mu_roll;
          r.model = model;
          r.body = body;
          r.contacts = contacts;
          r.targets.restitution = restitution;
          r.targets.contact_time = contact_time;
          r.targets.penetration = penetration;
          r.engine = engine;
          r.settle = settle;
          r.key = key;
          r.apply = apply;
          r.slope = slope;
          return py_solref(r);
        });
  m.attr("mujoco_available") = engines::mujoco_available();
}

}  // namespace

PYBIND11_MODULE(_contact2d, m) {
  m.doc() = "contact2d's libraries (the Python half: contact2d/__init__.py, docs/python.md)";
  bind_exceptions();
  bind_scene_parts(m);
  bind_scene(m);
  bind_commands(m);
}
