#pragma once
// The Python module specula._specula (python/specula/__init__.py re-exports it): shared pieces of
// the binding — the model object, reading a model argument, long calls that release the GIL and
// stop on Ctrl-C.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <future>
#include <optional>
#include <string>

#include "specula/catalogue/catalogue.h"
#include "specula/interrupt/interrupt.h"

namespace specula::python {

namespace py = pybind11;

/// A model as Python holds it: the Model, and what made it (for repr and pickling).
struct PyModel {
  std::string id;            ///< an id, "lobe: …" or "brdf: …"
  std::optional<Form> form;  ///< as asked (else the model's own)
  std::optional<double> coef;
  ParamValues params;        ///< as given (others at their defaults)
  Model model;
};

/// The model of `id` with `params`, `form` and `coef` (ValueError naming what is wrong).
PyModel make_py_model(const std::string& id, const ParamValues& params, std::optional<std::string> form,
                      std::optional<double> coef);
/// A model argument: a Model object, or an id or inline definition (then made at its defaults).
const PyModel& model_argument(const py::object& argument, std::optional<PyModel>& storage);

/// Runs `work` on a worker thread under a cancel flag, the GIL released; Ctrl-C in Python sets
/// the flag (the library's interrupt checks stop the work within its next check) and raises
/// KeyboardInterrupt here.
template <class Work>
auto run_interruptible(Work&& work) -> decltype(work()) {
  std::atomic<bool> cancel{false};
  auto future = std::async(std::launch::async, [&] {
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

void bind_models(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace specula::python
