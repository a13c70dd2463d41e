#pragma once
// The Python module specula._specula (python/specula/__init__.py re-exports it): shared pieces of
// the binding — the model object, reading a model argument, long calls that release the GIL and
// stop on Ctrl-C, arrays read a chunk at a time, and the checks every bound class shares (an
// instance made without a constructor, pickling).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <future>
#include <memory>
#include <optional>
#include <shared_mutex>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "specula/analysis/check.h"
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

/// About how long a chunk of an array call works: Ctrl-C stops a call within one chunk's work.
inline constexpr std::chrono::milliseconds kChunkTime{10};
/// The first chunk's elements, and the fewest a chunk holds.
inline constexpr std::size_t kFirstChunk = 256;
/// The most elements a chunk holds: values (the lobe's cosines, a formula's rows), or directions
/// (a model's values, samples, densities). A strided input's buffer holds a chunk.
inline constexpr std::size_t kMaxChunkValues = std::size_t{1} << 18, kMaxChunkRows = std::size_t{1} << 16;

/// The elements of the chunk after one of `done` elements that took `took`: as many as take about
/// kChunkTime at that pace, at most four times as many, within [kFirstChunk, most].
inline std::size_t next_chunk(std::size_t done, std::chrono::steady_clock::duration took, std::size_t most) {
  const double paced = static_cast<double>(done) * (std::chrono::duration<double>(kChunkTime) / took);  // inf for 0 s
  const double next = std::min({paced, 4.0 * static_cast<double>(done), static_cast<double>(most)});
  return std::max(kFirstChunk, static_cast<std::size_t>(next));
}

/// Runs body(begin, end) over [0, count) a chunk at a time with the GIL released, and raises
/// KeyboardInterrupt for Ctrl-C between chunks. Chunks are sized by time (next_chunk), so that a
/// call stops within about kChunkTime of work whatever an element costs (a formula lobe's can be
/// microseconds; a sanitizer's build is several times slower).
template <class Body>
void for_chunks(std::size_t count, std::size_t most, const Body& body) {
  std::size_t chunk = kFirstChunk;
  for (std::size_t begin = 0; begin < count;) {
    const std::size_t end = begin + std::min(chunk, count - begin);
    const auto start = std::chrono::steady_clock::now();
    {
      const py::gil_scoped_release release;
      body(begin, end);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    chunk = next_chunk(end - begin, std::chrono::steady_clock::now() - start, most);
    begin = end;
  }
}

/// The elements of an array of T in C order, a chunk at a time, as contiguous memory: the array's
/// own when it is C-contiguous and aligned, else copied through its strides (a broadcast view's
/// zero strides included) into a chunk-sized buffer, so that no call copies a whole input.
/// chunk() needs no GIL.
template <class T>
class Elements {
 public:
  /// `a`'s elements; `out` (or None) is the array the call writes: an input that overlaps it
  /// (other than element for element, in place) is copied whole first, as a chunk must not read
  /// what an earlier chunk wrote.
  Elements(const py::array_t<T>& a, const py::object& out)
      : array_(overlaps(a, out) ? py::array_t<T>(a.attr("copy")()) : a),
        data_(reinterpret_cast<const char*>(array_.data())),
        shape_(array_.shape(), array_.shape() + array_.ndim()),
        strides_(array_.strides(), array_.strides() + array_.ndim()),
        contiguous_((array_.flags() & py::array::c_style) &&
                    (array_.flags() & py::detail::npy_api::NPY_ARRAY_ALIGNED_)) {
    if (shape_.empty()) {  // a 0-d array: one element
      shape_ = {1};
      strides_ = {0};
    }
  }

  std::size_t size() const noexcept { return static_cast<std::size_t>(array_.size()); }

  /// Elements [begin, end).
  std::span<const T> chunk(std::size_t begin, std::size_t end) {
    if (contiguous_) return {reinterpret_cast<const T*>(data_) + begin, end - begin};
    buffer_.resize(end - begin);
    gather(static_cast<py::ssize_t>(begin));
    return buffer_;
  }

 private:
  static bool overlaps(const py::array_t<T>& a, const py::object& out) {
    if (out.is_none() || !py::cast<bool>(py::module_::import("numpy").attr("may_share_memory")(a, out))) return false;
    const auto same = py::reinterpret_borrow<py::array>(out);
    return same.data() != a.data() || !(a.flags() & py::array::c_style) || same.itemsize() != a.itemsize();
  }

  /// buffer_'s elements from element `begin` on, walking the index like an odometer (the last
  /// axis fastest).
  void gather(py::ssize_t begin) {
    const std::size_t last = shape_.size() - 1;
    std::vector<py::ssize_t> index(shape_.size());
    py::ssize_t offset = 0;
    for (std::size_t k = shape_.size(); k-- > 0; begin /= shape_[k]) {
      index[k] = begin % shape_[k];
      offset += index[k] * strides_[k];
    }
    for (std::size_t filled = 0; filled < buffer_.size();) {
      const auto run = std::min(static_cast<py::ssize_t>(buffer_.size() - filled), shape_[last] - index[last]);
      for (py::ssize_t i = 0; i < run; ++i)
        std::memcpy(&buffer_[filled++], data_ + offset + i * strides_[last], sizeof(T));  // unaligned too
      index[last] += run;
      offset += run * strides_[last];
      for (std::size_t k = last; k > 0 && index[k] == shape_[k]; --k) {  // carry into the axis before
        offset += strides_[k - 1] - shape_[k] * strides_[k];
        index[k] = 0;
        ++index[k - 1];
      }
    }
  }

  py::array_t<T> array_;  ///< keeps the memory alive
  const char* data_;
  std::vector<py::ssize_t> shape_, strides_;
  bool contiguous_;
  std::vector<T> buffer_;
};

/// pybind11's caster of a bound class T that also refuses, with TypeError, an instance Python made
/// without a constructor (T.__new__(T)): pybind11 would hand the method uninitialised memory for
/// it. Every bound class's caster is this one (the end of this file; search.cpp's classes), so
/// that every method, property and model argument checks its instance.
template <class T>
struct ConstructedCaster : py::detail::type_caster_base<T> {
  bool load(py::handle src, bool convert) {
    if (py::isinstance<T>(src) && !constructed(src))
      throw py::type_error("this specula." + std::string(py::str(py::type::handle_of<T>().attr("__name__"))) +
                           " was made by __new__ without a constructor: use one that specula returns");
    return py::detail::type_caster_base<T>::load(src, convert);
  }

 private:
  /// Whether `src` holds a T: pybind11 sets its value pointer only by constructing (or
  /// referencing) one; a bare __new__ leaves it null.
  static bool constructed(py::handle src) {
    auto* instance = reinterpret_cast<py::detail::instance*>(src.ptr());
    return static_cast<bool>(instance->get_value_and_holder(py::detail::get_type_info(typeid(T))));
  }
};

/// Pickling refused at every protocol with TypeError, as Python refuses it at protocol 2 and above
/// for a class without pickling support (at protocols 0 and 1 copyreg would call pybind11's base
/// type, which aborts the interpreter).
template <class T>
void refuse_pickling(py::class_<T>& bound) {
  bound.def("__reduce__", [](const py::handle& self) -> py::object {
    throw py::type_error("cannot pickle 'specula." + std::string(py::str(py::type::of(self).attr("__name__"))) +
                         "' object");
  });
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
/// The number of 3-vectors of an array of shape (..., 3) (ValueError naming it otherwise).
std::size_t vector_count(const py::array_t<double>& a, const char* name);

/// Binds models() … and the Model class, which it returns for the other parts to add methods to.
py::class_<PyModel> bind_models(py::module_& m);
void bind_analysis(py::module_& m);
void bind_sampling(py::module_& m, py::class_<PyModel>& model_class);
void bind_pictures(py::module_& m);
void bind_search(py::module_& m);

}  // namespace specula::python

// The bound classes of binding.h check their instance (ConstructedCaster).
template <>
struct pybind11::detail::type_caster<specula::python::PyModel>
    : specula::python::ConstructedCaster<specula::python::PyModel> {};
template <>
struct pybind11::detail::type_caster<specula::analysis::CheckResult>
    : specula::python::ConstructedCaster<specula::analysis::CheckResult> {};
