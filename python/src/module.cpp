// specula._specula: the binding's entry point. Bad input is ValueError (TypeError for a wrong
// kind of argument) with the CLI's one-line message; a stop is KeyboardInterrupt.
#include "binding.h"
#include "specula/exceptions.h"

PYBIND11_MODULE(_specula, m) {
  namespace py = pybind11;
  m.doc() = "specula's library from Python (docs/python.md)";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const specula::InvalidArgument& e) {  // InvalidField too: the message names the field
      PyErr_SetString(PyExc_ValueError, specula::one_line(e.what()).c_str());
    } catch (const specula::Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  auto model_class = specula::python::bind_models(m);
  specula::python::bind_analysis(m);
  specula::python::bind_sampling(m, model_class);
  specula::python::bind_pictures(m);
  specula::python::bind_search(m);
}
