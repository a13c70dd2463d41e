#pragma once
// The Python module specula._specula (python/specula/__init__.py re-exports it): shared pieces of
// the binding — the model object, reading a model argument, long calls that release the GIL and
// stop on Ctrl-C.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/interrupt/interrupt.h"
#include "specula/sampling/sampler.h"

namespace specula::python {

namespace py = pybind11;

/// A model as Python holds it: the Model, and what made it (for repr and pickling).
struct PyModel {
  std::string id;            ///< an id, "lobe: …" or "brdf: …"
  std::optional<Form> form;  ///< as asked (else the model's own)
  std::optional<double> coef;
  ParamValues params;        ///< as given (others at their defaults)
  Model model;
  /// Made at the first sample() or pdf() (tables: a few ms), then kept.
  mutable std::shared_ptr<const sampling::Sampler> sampler;
};

/// The model of `id` with `params`, `form` and `coef` (ValueError naming what is wrong).
PyModel make_py_model(const std::string& id, const ParamValues& params, std::optional<std::string> form,
                      std::optional<double> coef);
/// A model argument: a Model object, or an id or inline definition (then made at its defaults).
const PyModel& model_argument(const py::object& argument, std::optional<PyModel>& storage);

/// Guards the catalogue: long calls read it (shared), load_models and clear_models change it
/// (exclusive), so that no model file is registered while a worker looks a model up.
std::shared_mutex& catalogue_mutex();

/// Runs `work` on a worker thread under a cancel flag, the GIL released; Ctrl-C in Python sets
/// the flag (the library's interrupt checks stop the work within its next check) and raises
/// KeyboardInterrupt here.
template <class Work>
auto run_interruptible(Work&& work) -> decltype(work()) {
  std::atomic<bool> cancel{false};
  auto future = std::async(std::launch::async, [&] {
    const std::shared_lock reading(catalogue_mutex());
    const ScopedLimit limit(WorkLimit{std::chrono::steady_clock::time_point::max(), &cancel});
    return work();
  });
  for (;;) {
    bool ready = false;
    {
      const py::gil_scoped_release release;
      ready = future.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
    }
    if (ready) return future.get();
    if (PyErr_CheckSignals() != 0) {
      cancel = true;
      {
        const py::gil_scoped_release release;
        future.wait();
      }
      try {
        future.get();
      } catch (const Interrupted&) {
      }
      throw py::error_already_set();
    }
  }
}

/// `text` as a Python string literal.
std::string python_repr(const std::string& text);

/// What a C++ type is called in a TypeError.
template <class T>
constexpr const char* kind_name() {
  if constexpr (std::is_same_v<T, bool>) return "True or False";
  else if constexpr (std::is_integral_v<T>) return "an integer";
  else if constexpr (std::is_floating_point_v<T>) return "a number";
  else if constexpr (std::is_same_v<T, std::string>) return "a string";
  else return "a list of strings";
}

/// `value` as a T, or TypeError naming the argument (not pybind11's RuntimeError of a cast).
template <class T>
T argument(const py::handle& value, std::string_view name) {
  const auto type_name = [&] { return std::string(py::str(py::type::of(value).attr("__name__"))); };
  if constexpr (std::is_same_v<T, bool>) {  // True or False only: no truth value of other objects
    if (!PyBool_Check(value.ptr()) && type_name() != "bool_")
      throw py::type_error(std::string(name) + " must be True or False, got " + type_name());
  }
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw py::type_error(std::string(name) + " must be " + kind_name<T>() + ", got " + type_name());
  }
}

/// `x` as a NumPy array of real numbers (bool, integer or floating point); TypeError naming the
/// argument for complex numbers, strings or objects (which a cast would turn silently into numbers).
py::array real_array(const py::handle& x, std::string_view name);
/// The values of a number or array argument as doubles (TypeError naming it otherwise).
std::vector<double> values_of(const py::object& x, const char* name);

/// Binds models() … and the Model class, which it returns for the other parts to add methods to.
py::class_<PyModel> bind_models(py::module_& m);
void bind_analysis(py::module_& m);
void bind_sampling(py::module_& m, py::class_<PyModel>& model_class);
void bind_pictures(py::module_& m);
void bind_search(py::module_& m);

}  // namespace specula::python
