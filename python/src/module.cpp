// The Python module sap_broadphase._sap_broadphase (pybind11): numpy arrays in, numpy arrays
// out. Boxes are (n, 6) rows min_x min_y min_z max_x max_y max_z of float64, float32 or
// integers in any layout, given to the engine as float64 (a BoxSpan: its one input): a
// C-contiguous float64 array is read where it lies, anything else is converted once, exactly
// (integers beyond 2^53 are refused: float64 cannot hold them). Pairs and hits are (k, 2)
// uint32 arrays that own their vectors. The GIL is released while the engine works; refusals
// carry the engine's words.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <type_traits>
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
    "an array of shape (n, 6) of float64, float32 or integers, rows min_x min_y min_z max_x max_y "
    "max_z";

// Every integer of magnitude up to 2^53 is a float64; above, some are not (2^53 + 1).
constexpr int64_t kExactIntegerLimit = int64_t{1} << 53;

std::string shapeText(const py::array& inArray) {
  std::string text = "(";
  for (py::ssize_t axis = 0; axis < inArray.ndim(); ++axis)
    text += (axis > 0 ? ", " : "") + std::to_string(inArray.shape(axis));
  return text + (inArray.ndim() == 1 ? ",)" : ")");
}

std::string dtypeText(const py::array& inArray) {
  return py::str(inArray.dtype()).cast<std::string>();
}

py::module_ numpy() {
  return py::module_::import("numpy");
}

// inValues as a numpy array: itself when it is one, else numpy.asarray's reading of it (lists,
// tuples); what numpy cannot read as an array is refused in the words of inExpected.
py::array asArray(const py::handle& inValues, const std::string& inExpected) {
  if (py::isinstance<py::array>(inValues)) return py::reinterpret_borrow<py::array>(inValues);
  try {
    return numpy().attr("asarray")(inValues);
  } catch (py::error_already_set& error) {
    throw py::value_error(inExpected + ", got " + error.what());
  }
}

// inArray converted to a C-contiguous, aligned array of inType: the array itself when it is
// one, else one copy (numpy.require).
template <typename Value>
py::array_t<Value, py::array::c_style> required(const py::array& inArray, const char* inType) {
  return numpy().attr("require")(inArray, inType, py::make_tuple("C", "A"));
}

// Integers convert to float64 exactly up to 2^53 in magnitude; 8-byte ones may lie beyond.
void checkExactInFloat64(const py::array& inArray, const std::string& inExpected) {
  if (inArray.dtype().itemsize() < 8 || inArray.size() == 0) return;
  const bool outside =
      inArray.dtype().kind() == 'u'
          ? inArray.attr("max")().cast<uint64_t>() > static_cast<uint64_t>(kExactIntegerLimit)
          : inArray.attr("max")().cast<int64_t>() > kExactIntegerLimit ||
                inArray.attr("min")().cast<int64_t>() < -kExactIntegerLimit;
  if (outside)
    throw py::value_error(inExpected + ", got " + dtypeText(inArray) + " values from " +
                          py::str(inArray.attr("min")()).cast<std::string>() + " to " +
                          py::str(inArray.attr("max")()).cast<std::string>() +
                          ": beyond 2^53 in magnitude an integer has no exact float64 "
                          "(convert with .astype(numpy.float64) to accept the rounding)");
}

// inBoxes as a C-contiguous float64 (n, 6) array. Read in place: a C-contiguous, aligned
// float64 array of native byte order. Copied once: float64 in another layout (Fortran order,
// strided, byte-swapped), float16/float32 and integers (exact: each is a float64), lists.
// Empty: shape (0, 6) or (0,) (`[]`). Refused: other dtypes (bool, complex, float128,
// objects, strings), other shapes, integers beyond 2^53.
py::array_t<double, py::array::c_style> boxArray(const py::handle& inBoxes, const char* inName) {
  const std::string expected = std::string(inName) + ": expected " + kBoxesExpected;
  const py::array array = asArray(inBoxes, expected);
  const char kind = array.dtype().kind();
  const bool floating = kind == 'f' && array.dtype().itemsize() <= 8;
  if (!floating && kind != 'i' && kind != 'u')
    throw py::value_error(expected + ", got dtype " + dtypeText(array));
  const bool empty = array.size() == 0 && array.ndim() == 1;
  if (!empty && (array.ndim() != 2 || array.shape(1) != 6))
    throw py::value_error(expected + ", got shape " + shapeText(array));
  if (!floating) checkExactInFloat64(array, expected);
  return required<double>(empty ? py::array(array.attr("reshape")(0, 6)) : array, "float64");
}

// An optional (n,) array of uint32 values (ids, groups, masks): empty for None. Read in place:
// a C-contiguous uint32 array; any other integer array or list is checked to lie in [0, 2^32)
// and copied once.
py::array_t<uint32_t, py::array::c_style> uintArray(const py::handle& inValues, py::ssize_t inCount,
                                                    const char* inName) {
  if (inValues.is_none()) return py::array_t<uint32_t, py::array::c_style>();
  const std::string expected = std::string(inName) + ": expected integers in [0, 2^32) of shape (" +
                               std::to_string(inCount) + ",)";
  const py::array array = asArray(inValues, expected);
  if (array.ndim() != 1 || array.shape(0) != inCount)
    throw py::value_error(expected + ", got shape " + shapeText(array));
  if (inCount == 0) return py::array_t<uint32_t, py::array::c_style>();  // `[]` is float64
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error(expected + ", got dtype " + dtypeText(array));
  if (!array.dtype().is(py::dtype::of<uint32_t>())) {
    const bool outside = (kind == 'i' && array.attr("min")().cast<int64_t>() < 0) ||
                         (array.dtype().itemsize() > 4 && array.attr("max")().cast<uint64_t>() >
                                                              std::numeric_limits<uint32_t>::max());
    if (outside)
      throw py::value_error(expected + ", got values from " +
                            py::str(array.attr("min")()).cast<std::string>() + " to " +
                            py::str(array.attr("max")()).cast<std::string>());
  }
  return required<uint32_t>(array, "uint32");
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

// A report field as Python holds it: an axis by its letter, a path or a skin choice by its name.
template <typename Value>
py::object reportValue(const sb::ReportField& inField, Value inValue) {
  if constexpr (std::is_same_v<Value, sb::FramePath> || std::is_same_v<Value, sb::SkinChoice>)
    return py::str(sb::reportValueText(inField.unit, inValue));
  else if constexpr (std::is_same_v<Value, int>)
    if (inField.unit == sb::ReportUnit::kAxis) return py::str(sb::axisName(inValue));
  return py::cast(inValue);
}

// Every field of the report's table (frame_report.h) by its name.
py::dict statsDict(const sb::FrameReport& inReport) {
  py::dict stats;
  sb::forEachReportField(inReport, [&](const sb::ReportField& inField, auto inValue) {
    stats[inField.name] = reportValue(inField, inValue);
  });
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

  // (began, ended): copies of the engine's lists, which the next update() replaces.
  py::tuple events() const {
    sb::PairList began, ended;
    {
      py::gil_scoped_release release;
      std::shared_lock<std::shared_mutex> lock(mutex_);
      const sb::ContactEvents& events = engine_.events();
      began = events.began;
      ended = events.ended;
    }
    return py::make_tuple(pairArray(std::move(began)), pairArray(std::move(ended)));
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

// A field's default as Python writes it: True, 0.25, 'auto'.
std::string pythonDefault(const sb::ConfigField& inField) {
  const std::string text = inField.default_text;
  switch (inField.type) {
    case sb::ConfigFieldType::kBool:
      return text == "true" ? "True" : "False";
    case sb::ConfigFieldType::kInteger:
    case sb::ConfigFieldType::kNumber:
      return text;
    default:
      return "'" + text + "'";
  }
}

// The class's docstring: its keywords are the rows of configFields(), each with its default,
// what it takes and what it does.
const char* broadphaseDoc() {
  static const std::string doc = [] {
    std::string text =
        "The stateful broad phase, frame after frame.\n\n"
        "Broadphase(**config): every BroadphaseConfig field by its name; see the config "
        "property. Keywords:\n";
    for (const sb::ConfigField& field : sb::configFields())
      text += std::string("\n") + field.name + " (default " + pythonDefault(field) +
              "): " + field.allowed + ". " + field.doc + ".";
    return text;
  }();
  return doc.c_str();
}

}  // namespace

PYBIND11_MODULE(_sap_broadphase, m) {
  m.doc() = "Exact parallel Sweep and Prune broad phase: overlapping pairs and box queries.";
  py::register_exception<sb::InvalidBoxes>(m, "InvalidBoxes", PyExc_ValueError);
  py::register_exception<sb::TooManyPairs>(m, "TooManyPairs", PyExc_ValueError);

  m.def("find_pairs", &findPairs, "boxes"_a, "ids"_a = py::none(), "threads"_a = 0,
        R"doc(Every overlapping pair of boxes (closed intervals: touching boxes overlap).

boxes: array-like of shape (n, 6) (or empty), rows min_x min_y min_z max_x max_y max_z, of
float64 (a C-contiguous one is read without a copy; other layouts are copied once), float32 or
integers (converted once to float64, exactly; integers beyond 2^53 in magnitude are refused).
ids: n integers in [0, 2^32) (default: row numbers). threads: 0 = all cores. Returns a uint32
array of shape (k, 2), rows (a, b) of ids with a < b, sorted. Raises ValueError: InvalidBoxes
naming the first bad box and why, or what was expected of an argument.)doc");

  m.def("_one_shot_ms", &oneShotMs, "boxes"_a, "threads"_a = 0,
        "Milliseconds of find_pairs' work in C++ alone (for benchmarks).");

  auto broadphase =
      py::class_<PyBroadphase>(m, "Broadphase", broadphaseDoc())
          .def(py::init<const py::kwargs&>())
          .def("update", &PyBroadphase::update, "boxes"_a, "ids"_a = py::none(),
               "groups"_a = py::none(), "masks"_a = py::none(),
               "The frame's overlapping pairs: uint32 (k, 2), rows (a, b) of ids, a < b, sorted.")
          .def(
              "query", &PyBroadphase::query, "boxes"_a, "groups"_a = py::none(),
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
  broadphase.def("events", &PyBroadphase::events,
                 R"doc(The contacts that began and ended at the last update(): (began, ended), two
uint32 arrays of shape (k, 2) sorted as update()'s pairs. began: the pairs of the last list absent
from the one before; ended: those of the one before absent from the last. After construction or
reset() every pair of the first frame begins; a frame that raised has none.)doc");
}
