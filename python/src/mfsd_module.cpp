// The Python module's native part, mfsd._mfsd (issue 28): the scene reader,
// the run session (host/driver/run_session.hpp) that `mfsd run` steps, and
// the solver's fields as NumPy arrays. No physics here: python/mfsd/ shapes
// the API, this file only exposes the library the CLI uses.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <string>
#include <vector>
#ifdef MFSD_HAVE_CUDA_RUNTIME
#include <cuda_runtime.h>
#endif

#include "host/backend/backend.hpp"
#include "host/cli/check_summary.hpp"
#include "host/driver/interrupt.hpp"
#include "host/driver/run_session.hpp"
#include "host/scene/particle_generator.hpp"
#include "host/scene/scene_error.hpp"
#include "host/scene/scene_reader.hpp"
#include "host/version.hpp"

namespace nb = nanobind;
using namespace nb::literals;

namespace mfsd {
namespace {

// A scene as read (overrides applied, every default resolved).
struct PyScene {
  SceneDocument doc;
  std::string name() const { return doc.scene.name; }
  int dimension() const { return doc.scene.dimension; }
  std::string resolved() const { return doc.resolved.dump(); }
  std::string source() const { return doc.source.dump(); }
  double end_time() const { return doc.scene.solver.end_time; }
  // What `mfsd check` prints: the particles generated, nothing written.
  std::string summary() const { return check_summary(doc, generate_particles(doc.scene)); }
};

PyScene scene_from_file(const std::string& path, const std::vector<std::string>& overrides) {
  return PyScene{load_scene_file(path, overrides)};
}
PyScene scene_from_text(const std::string& text, const std::string& source_name,
                        const std::vector<std::string>& overrides) {
  return PyScene{load_scene_text(text, source_name, overrides)};
}

// One run, stepped from Python. Its signal handlers are installed only while
// it steps, so Ctrl-C between steps is Python's KeyboardInterrupt, and
// within a step it takes the CLI's path (the step ends, then the caller
// finishes the run: checkpoint, last snapshot, exit state "interrupted").
class PySession {
 public:
  PySession(const PyScene& scene, const std::string& backend, int threads, const std::string& precision,
            const std::string& output_dir, bool quiet, long max_steps, const std::string& command_line) {
    RunOptions o;
    o.command_line = command_line;
    o.solver.precision = scene.doc.scene.solver.precision;
    if (backend != "cpu" && backend != "cuda")
      throw nb::value_error(("backend '" + backend + "': expected \"cpu\" or \"cuda\"").c_str());
    o.solver.backend = backend;
    if (threads < 0) throw nb::value_error(("threads " + std::to_string(threads) + ": expected >= 1").c_str());
    o.solver.threads = threads;
    if (!precision.empty()) {
      if (precision != "float" && precision != "double")
        throw nb::value_error(("precision '" + precision + "': expected \"float\" or \"double\"").c_str());
      o.solver.precision = precision == "float" ? Precision::single_precision : Precision::double_precision;
      o.precision_given = true;
    }
    o.output_dir = output_dir;
    o.quiet = quiet;
    o.max_steps = max_steps;
    o.handle_signals = false;
    o.keep_series = true;
    clear_interrupt();
    session_ = std::make_unique<RunSession>(scene.doc, o);
  }

  // Up to n steps (fewer when the run stops); the steps taken.
  long step(long n) {
    long done = 0;
    nb::gil_scoped_release release;
    InterruptHandling signals;
    while (done < n && session_->running()) {
      session_->step();
      ++done;
    }
    return done;
  }
  // Steps until the time reaches t (or the run stops); the steps taken.
  long advance_to(double t) {
    long done = 0;
    nb::gil_scoped_release release;
    InterruptHandling signals;
    while (session_->running() && session_->solver().time() < t) {
      session_->step();
      ++done;
    }
    return done;
  }

  bool running() const { return session_->running(); }
  bool interrupted() const { return interrupt_signal() != 0; }
  double time() { return session_->solver().time(); }
  long steps() { return session_->solver().steps(); }
  double end_time() const { return session_->end_time(); }
  std::string output_dir() const { return session_->output_dir(); }

  // name -> (layout) of every plain field.
  std::vector<std::string> field_names() {
    std::vector<std::string> names;
    for (const FieldMemory& m : session_->solver().fields()) names.push_back(m.name);
    return names;
  }

  // A field as an array: on the CPU a read-only view of the solver's own
  // buffer that keeps this session alive (`owner`); from a GPU a copy.
  nb::object field(const std::string& name, nb::handle owner) {
    const Layout l = layout(name);
    if (!l.memory.on_device) {
      nb::ndarray<nb::numpy, nb::ro> view(l.memory.data, l.shape.size(), l.shape.data(), owner, nullptr, l.type);
      return view.cast();
    }
    // A copy on the host, owned by a capsule.
    auto* bytes = new std::string(session_->solver().field_bytes(name));
    nb::capsule free(bytes, [](void* p) noexcept { delete static_cast<std::string*>(p); });
    nb::ndarray<nb::numpy> copy(bytes->data(), l.shape.size(), l.shape.data(), free, nullptr, l.type);
    return copy.cast();
  }

  // A field where it lies, CPU or GPU, without a copy: (a DLPack capsule
  // that keeps this session alive through `owner`, the DLPack device type,
  // the device id). The package wraps it in __dlpack__ / __dlpack_device__.
  nb::object dlpack(const std::string& name, nb::handle owner) {
    const Layout l = layout(name);
    const int device = l.memory.on_device ? nb::device::cuda::value : nb::device::cpu::value;
    int device_id = 0;
#ifdef MFSD_HAVE_CUDA_RUNTIME
    if (l.memory.on_device) cudaGetDevice(&device_id);
#endif
    nb::ndarray<nb::ro> view(l.memory.data, l.shape.size(), l.shape.data(), owner, nullptr, l.type, device, device_id);
    return nb::make_tuple(view.cast(), device, device_id);  // a DLPack capsule, and where it lies
  }

  std::map<std::string, std::pair<std::vector<std::string>, std::vector<std::vector<double>>>> series() const {
    std::map<std::string, std::pair<std::vector<std::string>, std::vector<std::vector<double>>>> out;
    for (const auto& [file, s] : session_->series()) out[file] = {s.columns, s.rows};
    return out;
  }

  // The current EnergySample's totals (the energies.csv row of now).
  std::map<std::string, double> timing() {
    std::map<std::string, double> t;
    const StageTimers& timers = session_->solver().timers();
    for (const auto& st : timers.stages()) t[st.first] = st.second;
    return t;
  }

  void write_snapshot() { session_->write_snapshot(); }
  std::string checkpoint(const std::string& folder) { return session_->write_checkpoint(folder); }

  // Ends the run: (exit code, state message); the failure's fields when a
  // numerical failure stopped it.
  nb::dict finish() {
    const RunResult& r = session_->finish();
    nb::dict d;
    d["exit_code"] = r.exit_code;
    d["message"] = r.message;
    d["steps"] = r.steps;
    d["time"] = r.time;
    d["output_dir"] = r.output_dir;
    const auto& f = session_->failure();
    if (f) {
      d["failure_step"] = f->step();
      d["failure_time"] = f->time();
      d["failure_particle"] = f->particle_id();
      d["failure_body"] = f->body();
      d["failure_field"] = f->field();
      d["failure_detail"] = f->detail();
      d["failure_message"] = std::string(f->what());
    }
    return d;
  }

 private:
  // A field's memory and its array shape ((n), (n, d) or (n, d, d)) and type.
  struct Layout {
    FieldMemory memory;
    std::vector<size_t> shape;
    nb::dlpack::dtype type;
  };
  Layout layout(const std::string& name) {
    for (const FieldMemory& m : session_->solver().fields()) {
      if (m.name != name) continue;
      Layout l{m, {m.count}, {}};
      if (m.rows > 0) {
        l.shape.push_back(size_t(m.rows));
        l.shape.push_back(size_t(m.rows));
      } else if (m.components > 1) {
        l.shape.push_back(size_t(m.components));
      }
      l.type = nb::dlpack::dtype{uint8_t(m.kind == 'f'   ? nb::dlpack::dtype_code::Float
                                         : m.kind == 'i' ? nb::dlpack::dtype_code::Int
                                                         : nb::dlpack::dtype_code::UInt),
                                 uint8_t(8 * m.scalar_bytes), 1};
      return l;
    }
    throw nb::key_error(("no particle field '" + name + "' (sim.fields lists them)").c_str());
  }

  std::unique_ptr<RunSession> session_;
};

}  // namespace
}  // namespace mfsd

NB_MODULE(_mfsd, m) {
  using namespace mfsd;
  m.doc() = "mfsd's native layer (use the mfsd package)";
  m.attr("__version__") = MFSD_VERSION;

  // SceneError carries its JSON path: NativeSceneError(message, path), which
  // the package raises as mfsd.SceneError.
  static nb::exception<SceneError> scene_error(m, "NativeSceneError", PyExc_ValueError);
  nb::register_exception_translator(
      [](const std::exception_ptr& p, void* type) {
        try {
          std::rethrow_exception(p);
        } catch (const SceneError& e) {
          nb::object args = nb::make_tuple(std::string(e.what()), e.path());
          PyErr_SetObject(static_cast<PyObject*>(type), args.ptr());
        } catch (const UsageError& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        }
      },
      scene_error.ptr());

  nb::class_<PyScene>(m, "NativeScene")
      .def_prop_ro("name", &PyScene::name)
      .def_prop_ro("dimension", &PyScene::dimension)
      .def_prop_ro("end_time", &PyScene::end_time)
      .def("resolved_json", &PyScene::resolved)
      .def("source_json", &PyScene::source)
      .def("summary", &PyScene::summary);
  m.def("scene_from_file", &scene_from_file, "path"_a, "overrides"_a);
  m.def("scene_from_text", &scene_from_text, "text"_a, "source_name"_a, "overrides"_a);

  nb::class_<PySession>(m, "NativeSession")
      .def(nb::init<const PyScene&, const std::string&, int, const std::string&, const std::string&, bool, long,
                    const std::string&>(),
           "scene"_a, "backend"_a, "threads"_a, "precision"_a, "output_dir"_a, "quiet"_a, "max_steps"_a,
           "command_line"_a)
      .def("step", &PySession::step, "n"_a)
      .def("advance_to", &PySession::advance_to, "t"_a)
      .def_prop_ro("running", &PySession::running)
      .def_prop_ro("interrupted", &PySession::interrupted)
      .def_prop_ro("time", &PySession::time)
      .def_prop_ro("steps", &PySession::steps)
      .def_prop_ro("end_time", &PySession::end_time)
      .def_prop_ro("output_dir", &PySession::output_dir)
      .def("field_names", &PySession::field_names)
      .def("field", &PySession::field, "name"_a, "owner"_a)
      .def("dlpack", &PySession::dlpack, "name"_a, "owner"_a)
      .def("series", &PySession::series)
      .def("timing", &PySession::timing)
      .def("write_snapshot", &PySession::write_snapshot)
      .def("checkpoint", &PySession::checkpoint, "folder"_a)
      .def("finish", &PySession::finish);
}
