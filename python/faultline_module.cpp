// `import faultline`: the Python module over core/ (issue 38). Datasets and frames as numpy
// arrays that view the frame's own memory, and sessions that run the journal's ops (JOURNAL.md)
// given as dicts, with undo, redo, save and load. Nothing here computes anything itself.
#include "core/data/dataset.hpp"
#include "core/io/input_error.hpp"
#include "core/session/command_args.hpp"
#include "core/session/session.hpp"
#include "core/session/session_json.hpp"
#include "core/synth/demo_model.hpp"
#include "core/synth/dump_writer.hpp"
#include "core/synth/planes_model.hpp"
#ifdef FAULTLINE_PYTHON_RENDER
#include "ui/viewport/session_figure.hpp"
#endif

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/session/fault_surface_request.hpp"
#include "core/session/journal.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace py = pybind11;
using namespace faultline;

namespace {

using FramePtr = std::shared_ptr<const core::Frame>;

// A read-only numpy view of `data` that keeps `owner` (the frame) alive as long as it lives.
template <typename T> py::array view(const FramePtr& owner, const std::vector<T>& data) {
    auto* keep = new FramePtr(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<FramePtr*>(p); });
    py::array out(py::dtype::of<T>(), {py::ssize_t(data.size())}, {py::ssize_t(sizeof(T))},
                  data.data(), base);
    py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return out;
}

core::Json toJson(const py::handle& obj) {
    const std::string text = py::module_::import("json").attr("dumps")(obj).cast<std::string>();
    return core::Json::parse(text);
}

py::object fromJson(const core::Json& j) {
    if (j.is_null())
        return py::none();
    return py::module_::import("json").attr("loads")(j.dump());
}

std::vector<std::string> pathsOf(const py::object& paths) {
    if (py::isinstance<py::str>(paths))
        return {paths.cast<std::string>()};
    std::vector<std::string> out;
    for (const auto& p : paths)
        out.push_back(py::str(p).cast<std::string>());
    return out;
}

// Runs `work` on a worker thread while the calling thread waits without the GIL; every 50 ms
// it takes the GIL so Python can handle signals. Ctrl+C sets `stop`: work that checks it (exports
// over frames, surfaces) ends early having changed nothing, and KeyboardInterrupt is raised
// here; work with no check finishes and takes effect, and Python raises KeyboardInterrupt right
// after it returns, as for any C call. Errors of the work are raised as they are.
template <typename F> auto interruptible(std::atomic<bool>& stop, F&& work) -> decltype(work()) {
    using R = decltype(work());
    stop = false;
    std::packaged_task<R()> task(std::forward<F>(work));
    std::future<R> result = task.get_future();
    bool interrupted = false;
    {
        py::gil_scoped_release release;
        std::thread worker(std::move(task));
        while (result.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
            py::gil_scoped_acquire acquire;
            if (PyErr_CheckSignals() != 0) {
                interrupted = true;
                stop = true;
                break;
            }
        }
        worker.join();
    }
    if (!interrupted)
        return result.get();
    try {
        if constexpr (std::is_void_v<R>) {
            result.get();
            PyErr_Clear();
            PyErr_SetInterrupt();
            return;
        } else {
            R value = result.get();
            PyErr_Clear();
            PyErr_SetInterrupt();
            return value;
        }
    } catch (const py::error_already_set&) {
        throw;
    } catch (...) {
        throw py::error_already_set(); // stopped at a check: the KeyboardInterrupt set above
    }
}

// The surface builder's interrupter, stopped by Ctrl+C.
struct StopFlag : core::Interrupter {
    std::atomic<bool>& stop;
    explicit StopFlag(std::atomic<bool>& s) : stop(s) {}
    bool wasInterrupted(int) override { return stop.load(); }
};

class PyFrame {
  public:
    explicit PyFrame(FramePtr f) : m_frame(std::move(f)) {}
    std::size_t size() const { return m_frame->size(); }
    py::array ids() const { return view(m_frame, m_frame->ids); }
    py::array x() const { return view(m_frame, m_frame->x); }
    py::array y() const { return view(m_frame, m_frame->y); }
    py::array z() const { return view(m_frame, m_frame->z); }
    py::array radius() const { return view(m_frame, m_frame->radius); }
    py::array positions() const { // the frame keeps x, y, z apart: an N x 3 copy
        const std::size_t n = m_frame->size();
        py::array_t<float> out({py::ssize_t(n), py::ssize_t(3)});
        auto a = out.mutable_unchecked<2>();
        for (std::size_t i = 0; i < n; ++i) {
            a(py::ssize_t(i), 0) = m_frame->x[i];
            a(py::ssize_t(i), 1) = m_frame->y[i];
            a(py::ssize_t(i), 2) = m_frame->z[i];
        }
        return out;
    }
    std::vector<std::string> columns() const {
        std::vector<std::string> out;
        for (const auto& c : m_frame->attributes)
            out.push_back(c.name);
        return out;
    }
    py::array column(const std::string& name) const {
        if (name == "x")
            return x();
        if (name == "y")
            return y();
        if (name == "z")
            return z();
        if (name == "radius")
            return radius();
        if (name == "id")
            return ids();
        const core::AttributeColumn* c = m_frame->attribute(name);
        if (!c)
            throw py::key_error("no column named '" + name + "' (columns: " +
                                py::str(py::cast(columns())).cast<std::string>() + ")");
        return c->type == core::ColumnType::Float32 ? view(m_frame, c->floats)
                                                    : view(m_frame, c->ints);
    }
    py::dict box() const {
        const core::SimulationBox& b = m_frame->box;
        py::dict d;
        d["lo"] = py::make_tuple(b.lo[0], b.lo[1], b.lo[2]);
        d["hi"] = py::make_tuple(b.hi[0], b.hi[1], b.hi[2]);
        d["periodic"] = py::make_tuple(b.periodic[0], b.periodic[1], b.periodic[2]);
        d["tilt"] = py::make_tuple(b.xy, b.xz, b.yz);
        d["triclinic"] = b.triclinic;
        d["from_file"] = b.known;
        return d;
    }
    const FramePtr& frame() const { return m_frame; }

  private:
    FramePtr m_frame;
};

class PyDataset {
  public:
    explicit PyDataset(std::shared_ptr<core::Dataset> ds) : m_ds(std::move(ds)) {}
    std::size_t size() const { return m_ds->frameCount(); }
    PyFrame frame(long long index) const {
        const long long n = static_cast<long long>(m_ds->frameCount());
        if (index < 0)
            index += n;
        if (index < 0 || index >= n)
            throw py::index_error("frame " + std::to_string(index) + " out of range 0.." +
                                  std::to_string(n - 1));
        FramePtr f;
        {
            py::gil_scoped_release release;
            f = m_ds->frame(std::size_t(index));
        }
        return PyFrame(std::move(f));
    }
    long long timestep(std::size_t index) const { return m_ds->location(index).timestep; }
    std::vector<std::string> notes() const { return m_ds->notes(); }
    const std::shared_ptr<core::Dataset>& dataset() const { return m_ds; }

  private:
    std::shared_ptr<core::Dataset> m_ds;
};

PyDataset openData(const py::object& paths) {
    const auto list = pathsOf(paths);
    std::shared_ptr<core::Dataset> ds;
    {
        py::gil_scoped_release release;
        ds = core::Dataset::open(list);
    }
    return PyDataset(std::move(ds));
}

class PySession {
  public:
    PySession() {
#ifdef FAULTLINE_PYTHON_RENDER
        ui::registerRenderOp(m_session); // the journal's render op, as faultline replay has it
#endif
    }
#ifdef FAULTLINE_PYTHON_RENDER
    // A view as the workbench and `faultline render` draw it: H x W x 4 uint8 (RGBA), offscreen
    // (a hidden window with a display, EGL without one).
    py::array render(const std::string& view, std::pair<int, int> size,
                     std::optional<std::size_t> frame, bool transparent) {
        ui::FigureRequest request;
        request.view = view;
        request.width = size.first;
        request.height = size.second;
        request.frame = frame;
        request.transparent = transparent;
        ui::RgbaImage image;
        {
            py::gil_scoped_release release;
            image = ui::renderSessionImage(m_session, request);
        }
        py::array_t<std::uint8_t> out(
            {py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
        std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size());
        return out;
    }
#endif
    py::object run(const py::dict& cmd) {
        const core::Json j = toJson(cmd);
        // An expectation line ({"expect": "visible_count", "equals": 12}) is checked as
        // `faultline replay` checks it: AssertionError with "expected .., actual .." when not.
        if (j.is_object() && j.contains("expect")) {
            if (!j["expect"].is_string() ||
                !core::isKnownExpectation(j["expect"].get<std::string>()))
                throw core::CommandError("unknown expectation " + j["expect"].dump());
            std::optional<std::string> failed;
            {
                py::gil_scoped_release release;
                failed = core::checkExpectation(m_session, j);
            }
            if (failed) {
                PyErr_SetString(PyExc_AssertionError, (j.dump() + ": " + *failed).c_str());
                throw py::error_already_set();
            }
            return py::none();
        }
        // Rendering keeps to this thread (its offscreen GL context is current here); anything
        // else runs where Ctrl+C can stop it.
        // (Not value("op", ...): an "op" that is no string goes on to the session's own error.)
        if (j.is_object() && j.contains("op") && j["op"] == "render") {
            py::gil_scoped_release release;
            m_session.apply(j);
            return py::none();
        }
        m_session.setInterruptCheck([this] { return m_stop.load(); });
        interruptible(m_stop, [&] { m_session.apply(j); });
        return py::none();
    }
    // A fault's surface in the current frame, as export.gltf builds it: vertices (N x 3 float32,
    // the model's coordinates), triangles (M x 3 uint32, counter-clockwise from outside),
    // colours (N x 3 float32 RGB in 0..1) and normals (N x 3 float32).
    py::dict surface(const std::string& fault) {
        const core::FaultSurfaceRequest request =
            core::surfaceRequestFor(m_session, fault, "surface");
        const auto frame = m_session.currentFrame();
        if (!frame)
            throw core::CommandError("surface: no data is open");
        // The session's surfaces of this frame: one built by surface.build is not built again.
        const core::SurfaceReuse reuse = core::surfaceReuseFor(m_session, m_session.state().frame);
        core::SurfaceResult built = interruptible(m_stop, [&] {
            StopFlag flag(m_stop);
            return core::buildFaultSurface(*frame, request, &flag, reuse);
        });
        const core::SurfaceMesh& mesh = built.mesh;
        auto rows = [](const std::vector<std::array<float, 3>>& v) {
            py::array_t<float> out({py::ssize_t(v.size()), py::ssize_t(3)});
            if (!v.empty())
                std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(v[0]));
            return out;
        };
        py::array_t<std::uint32_t> triangles({py::ssize_t(mesh.triangleCount()), py::ssize_t(3)});
        if (!mesh.indices.empty())
            std::memcpy(triangles.mutable_data(), mesh.indices.data(),
                        mesh.indices.size() * sizeof(std::uint32_t));
        py::dict out;
        out["vertices"] = rows(mesh.positions);
        out["triangles"] = triangles;
        out["colours"] = rows(mesh.colors);
        out["normals"] = rows(mesh.normals);
        out["iso"] = built.iso;
        return out;
    }
    bool undo() {
        py::gil_scoped_release release;
        return m_session.undo();
    }
    bool redo() {
        py::gil_scoped_release release;
        return m_session.redo();
    }
    void save(const std::string& path) {
        run(py::dict(py::arg("op") = "session.save", py::arg("path") = path));
    }
    py::object state() const { return fromJson(core::sessionToJson(m_session.state(), "")); }
    std::optional<PyDataset> dataset() const {
        if (!m_session.dataset())
            return std::nullopt;
        return PyDataset(m_session.dataset());
    }
    std::optional<PyFrame> frame() {
        FramePtr f;
        {
            py::gil_scoped_release release;
            f = m_session.currentFrame();
        }
        if (!f)
            return std::nullopt;
        return PyFrame(std::move(f));
    }
    py::array visible() {
        const core::VisibilityResult* v;
        {
            py::gil_scoped_release release;
            v = &m_session.visibility();
        }
        py::array_t<bool> out(py::ssize_t(v->mask.size()));
        auto a = out.mutable_unchecked<1>();
        for (std::size_t i = 0; i < v->mask.size(); ++i)
            a(py::ssize_t(i)) = v->mask[i] != 0;
        return out;
    }
    py::dict faults() const {
        py::dict d;
        for (const auto& f : m_session.state().faults)
            d[py::str(f.name)] = py::array_t<std::int64_t>(py::ssize_t(f.ids.size()), f.ids.data());
        return d;
    }
    // A CSV the core writes (export.csv), read back as a numpy structured array: the same
    // values the CLI and the workbench export, one column per field.
    py::object table(const std::string& what, const py::object& variables, bool onlyVisible) {
        namespace fs = std::filesystem;
        const fs::path dir =
            fs::temp_directory_path() /
            ("faultline-py-" + std::to_string(reinterpret_cast<std::uintptr_t>(this)));
        fs::create_directories(dir);
        const std::string path = (dir / (what + ".csv")).string();
        py::dict cmd(py::arg("op") = "export.csv", py::arg("what") = what, py::arg("path") = path);
        if (!variables.is_none())
            cmd["variables"] = variables;
        if (onlyVisible)
            cmd["only_visible"] = true;
        try {
            run(cmd);
        } catch (...) {
            fs::remove_all(dir);
            throw;
        }
        py::object np = py::module_::import("numpy");
        py::object out = np.attr("genfromtxt")(
            path, py::arg("delimiter") = ",", py::arg("names") = true,
            py::arg("dtype") = py::none(), py::arg("encoding") = "utf-8", py::arg("ndmin") = 1);
        fs::remove_all(dir);
        return out;
    }
    // As a pandas DataFrame when asked (ImportError saying so when pandas is missing).
    static py::object asTable(py::object array, bool pandas) {
        if (!pandas)
            return array;
        py::object pd;
        try {
            pd = py::module_::import("pandas");
        } catch (py::error_already_set&) {
            throw py::import_error(
                "pandas=True needs pandas (Debian: apt-get install python3-pandas)");
        }
        return pd.attr("DataFrame")(array);
    }
    bool canUndo() const { return m_session.canUndo(); }
    bool canRedo() const { return m_session.canRedo(); }
    std::string undoLabel() const { return m_session.undoLabel(); }

  private:
    core::Session m_session;
    std::atomic<bool> m_stop{false};
};

// faultline.generate.planes: the planted-planes model written as a LAMMPS dump, and its truth.
py::tuple generatePlanes(const std::string& size, const std::string& path, int seed) {
    core::PlanesModelOptions options;
    if (size == "network")
        options = core::planesNetworkOptions();
    else if (size == "small" || size == "medium" || size == "large")
        options = core::planesOptionsFor(size == "small"    ? core::ModelSize::Small
                                         : size == "medium" ? core::ModelSize::Medium
                                                            : core::ModelSize::Large);
    else
        throw py::value_error("size must be small, medium, large or network, not '" + size + "'");
    if (seed >= 0)
        options.seed = static_cast<std::uint64_t>(seed);
    std::string truth;
    {
        py::gil_scoped_release release;
        const core::PlanesModel model = core::generatePlanesModel(options);
        core::LammpsDumpWriter writer(path, path.ends_with(".gz") ? 1 : 0);
        for (const core::Frame& f : model.frames)
            writer.write(f, core::extensionDumpColumns());
        writer.close();
        truth = core::planesTruthJson(model);
    }
    return py::make_tuple(path, py::module_::import("json").attr("loads")(truth));
}

} // namespace

PYBIND11_MODULE(faultline, m) {
    m.doc() = R"doc(Faultline: find, name and follow faults in Discrete Element Models.

The same core as the workbench and `faultline replay`:

    import faultline
    ds = faultline.open("run/dump.*.gz")          # every reader; globs; .gz
    f = ds.frame(-1)                               # a frame: numpy views of its columns
    f.ids, f.x, f.radius, f["strain"]              # no copies (read-only views)
    s = faultline.Session("run/dump.*.gz")         # journal ops as dicts (JOURNAL.md)
    s.run({"op": "strain.add", "since_offset": -1, "prefix": "inc_"})
    s.run({"op": "threshold.add", "variable": "inc_shear_strain", "low": 0.15, "high": 1e30})
    s.run({"op": "fault.candidates", "min_size": 50})
    s.faults                                       # {"C1": ids, ...}
    s.save("analysis.faultline.json")              # opens in the workbench

Errors are Python exceptions with the messages the CLI prints: faultline.InputError (a file that
cannot be read: path, line or byte, what was expected) and faultline.CommandError (an op refused).
)doc";
    m.attr("__version__") = "0.1.0";
    static py::exception<core::InputError> inputError(m, "InputError", PyExc_ValueError);
    static py::exception<core::CommandError> commandError(m, "CommandError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const core::InputError& e) {
            inputError(e.what());
        } catch (const core::CommandError& e) {
            commandError(e.what());
        }
    });

    py::class_<PyFrame>(m, "Frame",
                        "One timestep's spheres. Arrays view the frame's memory (read-only); "
                        "`positions` is an N x 3 copy (the frame keeps x, y, z apart).")
        .def("__len__", &PyFrame::size)
        .def_property_readonly("ids", &PyFrame::ids, "particle ids (int64), a view")
        .def_property_readonly("x", &PyFrame::x, "x of the centres (float32), a view")
        .def_property_readonly("y", &PyFrame::y, "y of the centres (float32), a view")
        .def_property_readonly("z", &PyFrame::z, "z of the centres (float32), a view")
        .def_property_readonly("radius", &PyFrame::radius, "radii (float32), a view")
        .def_property_readonly("positions", &PyFrame::positions, "N x 3 centres (float32), a copy")
        .def_property_readonly("columns", &PyFrame::columns, "the variables' names, in file order")
        .def_property_readonly("box", &PyFrame::box, "the simulation box: lo, hi, periodic, tilt")
        .def("__getitem__", &PyFrame::column, py::arg("name"),
             "a variable (float32 or int32), or x, y, z, radius, id: a view")
        .def("__contains__", [](const PyFrame& f, const std::string& name) {
            return f.frame()->attribute(name) != nullptr || name == "x" || name == "y" ||
                   name == "z" || name == "radius" || name == "id";
        });

    py::class_<PyDataset>(m, "Dataset", "Frames of a DEM run, loaded lazily.")
        .def("__len__", &PyDataset::size)
        .def("frame", &PyDataset::frame, py::arg("index"), "frame `index` (negative: from the end)")
        .def("timestep", &PyDataset::timestep, py::arg("index"), "the timestep of frame `index`")
        .def_property_readonly("notes", &PyDataset::notes,
                               "what to know about how the files read: a file that ends inside a "
                               "frame (a run still writing, or stopped) keeps its complete frames, "
                               "and a note names the one left out");

    m.def("open", &openData, py::arg("paths"),
          "Open DEM output: one path, a glob (`dump.*.gz`) or a list of them; every reader "
          "(LAMMPS/LIGGGHTS dumps, VTK legacy and XML, CSV, Yade, MercuryDPM). Raises InputError.");

    py::module_ generate = m.def_submodule("generate", "The built-in model generators.");
    generate.def(
        "demo",
        [] {
            py::gil_scoped_release release;
            return core::ensureDemoModel();
        },
        "The demo model's dump (the 3-D extension block the workbench opens), generated once per "
        "user (one to two minutes) and reused.");
    generate.def(
        "planes", &generatePlanes, py::arg("size") = "small", py::arg("path") = "planes.dump.gz",
        py::arg("seed") = -1,
        "Planted planar faults in a block (small ~7k spheres, medium ~34k, large ~270k, "
        "network ~154k: crossing, ending and listric faults), written as a LAMMPS dump at "
        "`path`. Returns (path, truth): the faults' planes, throws and members per frame.");

    py::class_<PySession>(m, "Session",
                          "A Faultline session: the journal's ops (JOURNAL.md) as dicts.")
        .def(py::init([](const py::object& paths) {
                 auto s = std::make_unique<PySession>();
                 if (!paths.is_none())
                     s->run(py::dict(py::arg("op") = "data.open",
                                     py::arg("paths") = py::cast(pathsOf(paths))));
                 return s;
             }),
             py::arg("paths") = py::none(), "A new session, with data opened when paths are given.")
        .def_static(
            "load",
            [](const std::string& path) {
                auto s = std::make_unique<PySession>();
                s->run(py::dict(py::arg("op") = "session.open", py::arg("path") = path));
                return s;
            },
            py::arg("path"), "A saved session (.faultline.json), with its data.")
        .def("run", &PySession::run, py::arg("command"),
             "Run one journal op, e.g. {'op': 'fault.candidates', 'min_size': 50}, undo and redo "
             "included. Raises CommandError, having changed nothing. An expectation line "
             "({'expect': 'visible_count', 'equals': 12}) is checked as faultline replay checks "
             "it: AssertionError saying expected and actual when it does not hold.")
        .def("undo", &PySession::undo, "Undo the last change; False when there is none.")
        .def("redo", &PySession::redo, "Redo what undo reverted; False when there is none.")
        .def("save", &PySession::save, py::arg("path"),
             "Save (session.save): opens in the workbench.")
        .def_property_readonly("can_undo", &PySession::canUndo)
        .def_property_readonly("can_redo", &PySession::canRedo)
        .def_property_readonly("undo_label", &PySession::undoLabel,
                               "what undo would revert, in words")
        .def_property_readonly("state", &PySession::state,
                               "everything a saved session holds, as a dict")
        .def_property_readonly("dataset", &PySession::dataset, "the open data, or None")
        .def_property_readonly("frame", &PySession::frame, "the current frame, or None")
        .def_property_readonly("visible", &PySession::visible,
                               "per sphere of the current frame: passes the boxes, thresholds and "
                               "fault filter (a copy)")
        .def_property_readonly("faults", &PySession::faults, "{name: member ids} (copies)")
#ifdef FAULTLINE_PYTHON_RENDER
        .def("render", &PySession::render, py::arg("view") = "main",
             py::arg("size") = std::make_pair(1280, 720), py::arg("frame") = py::none(),
             py::arg("transparent") = false,
             "The view drawn offscreen as an H x W x 4 uint8 RGBA array (size is (width, height)); "
             "no display needed (EGL)")
#endif
        .def(
            "fault_metrics",
            [](PySession& s, bool pandas) {
                return PySession::asTable(s.table("fault_metrics", py::none(), false), pandas);
            },
            py::arg("pandas") = false,
            "Every fault's metrics in every frame (export.csv fault_metrics) as a numpy "
            "structured array (pandas=True: a DataFrame): frame, fault, count, dip, "
            "dip_direction, throw, ...")
        .def(
            "fault_growth",
            [](PySession& s, bool pandas) {
                return PySession::asTable(s.table("fault_growth", py::none(), false), pandas);
            },
            py::arg("pandas") = false,
            "The metrics of what each fault is in each frame, followed through time")
        .def(
            "fault_events",
            [](PySession& s, bool pandas) {
                return PySession::asTable(s.table("fault_events", py::none(), false), pandas);
            },
            py::arg("pandas") = false,
            "When faults appeared, linked and split: frame, kind, faults")
        .def(
            "spheres",
            [](PySession& s, const py::object& variables, bool onlyVisible, bool pandas) {
                return PySession::asTable(s.table("spheres", variables, onlyVisible), pandas);
            },
            py::arg("variables") = py::none(), py::arg("only_visible") = false,
            py::arg("pandas") = false,
            "The current frame's spheres: id and the variables asked for (export.csv spheres)")
        .def("surface", &PySession::surface, py::arg("fault"),
             "A fault's surface in the current frame, as export.gltf builds it, as a dict of "
             "arrays: vertices (N x 3 float32), triangles (M x 3 uint32), colours (N x 3, RGB "
             "0..1), normals (N x 3), and the iso-value used");
}
