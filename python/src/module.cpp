// The Python module sap_broadphase._sap_broadphase (pybind11): numpy arrays in, numpy arrays
// out. Boxes are (n, 6) float64 rows min_x min_y min_z max_x max_y max_z, read where they lie
// when C-contiguous (a BoxSpan over the array: the engine's one input); pairs and hits are (k, 2)
// uint32 arrays that own the engine's result vectors (no copy). The GIL is released while
// the engine works; refusals carry the engine's words.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"
#include "sap_broadphase/core/pair_set.h"

namespace py = pybind11;
namespace sb = sap_broadphase;

namespace {

using namespace pybind11::literals;

constexpr const char* kBoxesExpected =
    "a float64 array of shape (n, 6), rows min_x min_y min_z max_x max_y max_z";

std::string shapeText(const py::array& inArray) {
  std::string text = "(";
  for (py::ssize_t axis = 0; axis < inArray.ndim(); ++axis)
    text += (axis > 0 ? ", " : "") + std::to_string(inArray.shape(axis));
  return text + (inArray.ndim() == 1 ? ",)" : ")");
}

py::module_ numpy() {
  return py::module_::import("numpy");
}

// inBoxes as a C-contiguous float64 (n, 6) array: the array itself when it is one (no copy),
// a contiguous copy of another float64 array, a float64 conversion of anything else (lists).
py::array_t<double, py::array::c_style> boxArray(const py::handle& inBoxes, const char* inName) {
  py::array array;
  if (py::isinstance<py::array>(inBoxes)) {
    array = py::reinterpret_borrow<py::array>(inBoxes);
    if (!array.dtype().is(py::dtype::of<double>()))
      throw py::type_error(std::string(inName) + ": expected " + kBoxesExpected + ", got dtype " +
                           py::str(array.dtype()).cast<std::string>() +
                           " (convert with .astype(numpy.float64))");
  } else {
    array = numpy().attr("asarray")(inBoxes, "dtype"_a = "float64");
  }
  if (array.ndim() != 2 || array.shape(1) != 6)
    throw py::value_error(std::string(inName) + ": expected " + kBoxesExpected + ", got shape " +
                          shapeText(array));
  return numpy().attr("ascontiguousarray")(array);  // the same array when already contiguous
}

// An optional (n,) array of uint32 values (ids, groups, masks): empty for None.
py::array_t<uint32_t, py::array::c_style> uintArray(const py::handle& inValues, py::ssize_t inCount,
                                                    const char* inName) {
  if (inValues.is_none()) return py::array_t<uint32_t, py::array::c_style>();
  py::array array = numpy().attr("asarray")(inValues);
  const char kind = array.dtype().kind();
  const std::string expected = std::string(inName) + ": expected integers in [0, 2^32) of shape (" +
                               std::to_string(inCount) + ",)";
  if (kind != 'i' && kind != 'u')
    throw py::type_error(expected + ", got dtype " + py::str(array.dtype()).cast<std::string>());
  if (array.ndim() != 1 || array.shape(0) != inCount)
    throw py::value_error(expected + ", got shape " + shapeText(array));
  if (!array.dtype().is(py::dtype::of<uint32_t>()) && inCount > 0) {
    const auto lowest = array.attr("min")().cast<long double>();
    const auto highest = array.attr("max")().cast<long double>();
    if (lowest < 0 || highest > 4294967295.0L)
      throw py::value_error(expected + ", got values from " +
                            py::str(array.attr("min")()).cast<std::string>() + " to " +
                            py::str(array.attr("max")()).cast<std::string>());
    array = array.attr("astype")("uint32");
  }
  return numpy().attr("ascontiguousarray")(array);
}

// The arrays a call reads, kept alive while the engine reads them without the GIL.
struct BoxArgs {
  py::array_t<double, py::array::c_style> bounds;
  py::array_t<uint32_t, py::array::c_style> ids, groups, masks;

  BoxArgs(const py::handle& inBoxes, const py::handle& inIds, const py::handle& inGroups,
          const py::handle& inMasks)
      : bounds(boxArray(inBoxes, "boxes")),
        ids(uintArray(inIds, bounds.shape(0), "ids")),
        groups(uintArray(inGroups, bounds.shape(0), "groups")),
        masks(uintArray(inMasks, bounds.shape(0), "masks")) {}

  sb::BoxSpan view() const {
    sb::BoxSpan records;
    records.count = static_cast<std::size_t>(bounds.shape(0));
    records.bounds = bounds.data();
    records.ids = ids.size() > 0 ? ids.data() : nullptr;
    records.groups = groups.size() > 0 ? groups.data() : nullptr;
    records.masks = masks.size() > 0 ? masks.data() : nullptr;
    return records;
  }
};

// A (k, 2) uint32 array that owns inRecords (pairs or hits: two uint32 each).
template <typename Record>
py::array_t<uint32_t> pairArray(std::vector<Record>&& inRecords) {
  static_assert(sizeof(Record) == 2 * sizeof(uint32_t), "a record is two uint32");
  auto* held = new std::vector<Record>(std::move(inRecords));
  py::capsule owner(held, [](void* inHeld) { delete static_cast<std::vector<Record>*>(inHeld); });
  const py::ssize_t rows = static_cast<py::ssize_t>(held->size());
  return py::array_t<uint32_t>({rows, py::ssize_t{2}},
                               {py::ssize_t{2 * sizeof(uint32_t)}, py::ssize_t{sizeof(uint32_t)}},
                               reinterpret_cast<const uint32_t*>(held->data()), owner);
}

sb::ConfigValue configValue(const std::string& inName, const py::handle& inValue) {
  if (py::isinstance<py::bool_>(inValue)) return inValue.cast<bool>();
  if (py::isinstance<py::int_>(inValue)) {
    // An int beyond int64 goes on as the number it is (infinite past a double), so that the
    // field's row refuses it in words (ValueError), not pybind11's cast (RuntimeError).
    int overflow = 0;
    const long long integer = PyLong_AsLongLongAndOverflow(inValue.ptr(), &overflow);
    if (overflow == 0) return static_cast<int64_t>(integer);
    const double number = PyLong_AsDouble(inValue.ptr());
    if (number != -1.0 || !PyErr_Occurred()) return number;
    PyErr_Clear();  // past a double
    return overflow * std::numeric_limits<double>::infinity();
  }
  if (py::isinstance<py::float_>(inValue)) return inValue.cast<double>();
  if (py::isinstance<py::str>(inValue)) return inValue.cast<std::string>();
  if (inValue.is_none() && inName == "skin") return std::string("auto");
  throw py::type_error(inName + ": expected a bool, int, float or str, got " +
                       py::str(py::type::of(inValue).attr("__name__")).cast<std::string>());
}

py::object pythonValue(const sb::ConfigValue& inValue) {
  return std::visit([](const auto& inHeld) -> py::object { return py::cast(inHeld); }, inValue);
}

std::string fieldNames() {
  std::string names;
  for (const sb::ConfigField& field : sb::configFields())
    names += (names.empty() ? "" : ", ") + std::string(field.name);
  return names;
}

// Every keyword a BroadphaseConfig field, checked by its row of configFields().
sb::BroadphaseConfig configOf(const py::kwargs& inOptions) {
  sb::BroadphaseConfig config;
  for (const auto& [key, value] : inOptions) {
    const std::string name = key.cast<std::string>();
    const sb::ConfigField* field = sb::findConfigField(name);
    if (field == nullptr)
      throw py::type_error("Broadphase() got an unexpected keyword argument '" + name +
                           "'; the options are " + fieldNames());
    if (auto problem = field->set(config, configValue(name, value)))
      throw py::value_error(name + ": " + *problem);
  }
  return config;
}

py::dict configDict(const sb::BroadphaseConfig& inConfig) {
  py::dict options;
  for (const sb::ConfigField& field : sb::configFields())
    options[field.name] = pythonValue(field.get(inConfig));
  return options;
}

py::dict statsDict(const sb::FrameReport& inReport) {
  py::dict stats;
  stats["boxes"] = inReport.boxes;
  stats["boxes_filtered_out"] = inReport.boxes_filtered_out;
  stats["pairs"] = inReport.pairs;
  stats["path"] = sb::framePathName(inReport.path);
  stats["threads"] = inReport.threads;
  stats["primary_axis"] = sb::axisName(inReport.primary_axis);
  stats["secondary_axis"] = sb::axisName(inReport.secondary_axis);
  stats["dispersion_primary"] = inReport.dispersion_primary;
  stats["dispersion_secondary"] = inReport.dispersion_secondary;
  stats["axes_swapped"] = inReport.axes_swapped;
  stats["slabs"] = inReport.slabs;
  stats["skin"] = inReport.skin;
  stats["skin_choice"] = sb::skinChoiceName(inReport.skin_choice);
  stats["skin_candidates"] = inReport.skin_candidates;
  stats["static_boxes"] = inReport.static_boxes;
  stats["moved_boxes"] = inReport.moved_boxes;
  stats["max_displacement"] = inReport.max_displacement;
  stats["ms_plan"] = inReport.ms_plan;
  stats["ms_history"] = inReport.ms_history;
  stats["ms_keys"] = inReport.ms_keys;
  stats["ms_sort"] = inReport.ms_sort;
  stats["ms_candidates"] = inReport.ms_candidates;
  stats["ms_pairing"] = inReport.ms_pairing;
  stats["ms_skin"] = inReport.ms_skin;
  stats["ms_static"] = inReport.ms_static;
  stats["ms_output"] = inReport.ms_output;
  stats["ms_total"] = inReport.ms_total;
  return stats;
}

// The engine and the lock that keeps the engine's thread contract for Python threads: queries
// share it, everything that changes the engine takes it alone (broadphase.h, query()).
class PyBroadphase {
 public:
  explicit PyBroadphase(const py::kwargs& inOptions) : engine_(configOf(inOptions)) {}

  py::array_t<uint32_t> update(const py::handle& inBoxes, const py::handle& inIds,
                               const py::handle& inGroups, const py::handle& inMasks) {
    const BoxArgs args(inBoxes, inIds, inGroups, inMasks);
    sb::PairList pairs;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::shared_mutex> lock(mutex_);
      pairs = engine_.update(args.view());  // the engine's list is reused by the next frame
    }
    return pairArray(std::move(pairs));
  }

  py::array_t<uint32_t> query(const py::handle& inBoxes, const py::handle& inGroups,
                              const py::handle& inMasks) const {
    const BoxArgs args(inBoxes, py::none(), inGroups, inMasks);
    sb::QueryHitList hits;
    {
      py::gil_scoped_release release;
      std::shared_lock<std::shared_mutex> lock(mutex_);
      hits = engine_.query(args.view());
    }
    return pairArray(std::move(hits));
  }

  void setStaticBoxes(const py::handle& inBoxes, const py::handle& inIds,
                      const py::handle& inGroups, const py::handle& inMasks) {
    const BoxArgs args(inBoxes, inIds, inGroups, inMasks);
    py::gil_scoped_release release;
    std::unique_lock<std::shared_mutex> lock(mutex_);
    engine_.setStaticBoxes(
        args.view());  // checks the boxes: a bad one leaves the scenery as it was
  }

  template <typename Change>
  void alone(Change&& inChange) {
    py::gil_scoped_release release;
    std::unique_lock<std::shared_mutex> lock(mutex_);
    inChange(engine_);
  }

  py::dict stats() const {
    std::shared_lock<std::shared_mutex> lock(mutex_);
    return statsDict(engine_.stats());
  }
  py::dict config() const { return configDict(engine_.config()); }
  std::size_t staticBoxCount() const {
    std::shared_lock<std::shared_mutex> lock(mutex_);
    return engine_.staticBoxCount();
  }

 private:
  sb::Broadphase engine_;
  mutable std::shared_mutex mutex_;
};

py::array_t<uint32_t> findPairs(const py::handle& inBoxes, const py::handle& inIds, int inThreads) {
  const BoxArgs args(inBoxes, inIds, py::none(), py::none());
  sb::BroadphaseConfig config;
  config.threads = inThreads;
  sb::PairList pairs;
  {
    py::gil_scoped_release release;
    sb::Broadphase engine(config);
    pairs = engine.update(args.view());
  }
  return pairArray(std::move(pairs));
}

// What find_pairs() costs in C++ alone (the engine made and run on the same memory), for the
// Python benchmark's comparison with the binding.
double oneShotMs(const py::handle& inBoxes, int inThreads) {
  const BoxArgs args(inBoxes, py::none(), py::none(), py::none());
  py::gil_scoped_release release;
  const auto start = std::chrono::steady_clock::now();
  sb::BroadphaseConfig config;
  config.threads = inThreads;
  sb::Broadphase engine(config);
  engine.update(args.view());
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

PYBIND11_MODULE(_sap_broadphase, m) {
  m.doc() = "Exact parallel Sweep and Prune broad phase: overlapping pairs and box queries.";
  py::register_exception<sb::InvalidBoxes>(m, "InvalidBoxes", PyExc_ValueError);

  m.def("find_pairs", &findPairs, "boxes"_a, "ids"_a = py::none(), "threads"_a = 0,
        R"doc(Every overlapping pair of boxes (closed intervals: touching boxes overlap).

boxes: array-like of shape (n, 6), float64 rows min_x min_y min_z max_x max_y max_z (a
C-contiguous float64 array is read without a copy). ids: n uint32 ids (default: row numbers).
threads: 0 = all cores. Returns a uint32 array of shape (k, 2), rows (a, b) of ids with a < b,
sorted. Raises ValueError (InvalidBoxes) naming the first bad box and why.)doc");

  m.def("_one_shot_ms", &oneShotMs, "boxes"_a, "threads"_a = 0,
        "Milliseconds of find_pairs' work in C++ alone (for benchmarks).");

  py::class_<PyBroadphase>(m, "Broadphase", R"doc(The stateful broad phase, frame after frame.

Broadphase(**config): every BroadphaseConfig field by its name (threads, method, primary_axis,
secondary_axis, axis_swapping, axis_swap_threshold, parallel_min_boxes, third_axis_slabs,
reuse_unchanged_frames, skin, exact_final_test); see the config property.)doc")
      .def(py::init<const py::kwargs&>())
      .def("update", &PyBroadphase::update, "boxes"_a, "ids"_a = py::none(),
           "groups"_a = py::none(), "masks"_a = py::none(),
           "The frame's overlapping pairs: uint32 (k, 2), rows (a, b) of ids, a < b, sorted.")
      .def("query", &PyBroadphase::query, "boxes"_a, "groups"_a = py::none(),
           "masks"_a = py::none(),
           "What overlaps each query box in the last frame and the scenery: uint32 (k, 2), rows "
           "(query row, world id), sorted.")
      .def("set_static_boxes", &PyBroadphase::setStaticBoxes, "boxes"_a, "ids"_a = py::none(),
           "groups"_a = py::none(), "masks"_a = py::none(),
           "Declares scenery (replacing any earlier): paired with every later frame's boxes.")
      .def("clear_static_boxes",
           [](PyBroadphase& inSelf) {
             inSelf.alone([](sb::Broadphase& ioEngine) { ioEngine.clearStaticBoxes(); });
           })
      .def("reset",
           [](PyBroadphase& inSelf) {
             inSelf.alone([](sb::Broadphase& ioEngine) { ioEngine.reset(); });
           })
      .def_property_readonly("stats", &PyBroadphase::stats, "The last update()'s report.")
      .def_property_readonly("config", &PyBroadphase::config, "The configuration in force.")
      .def_property_readonly("static_box_count", &PyBroadphase::staticBoxCount);
}
