// Model.sample, Model.pdf and specula.check_sampling: the importance sampler of every model
// (sampling/sampler.h) over NumPy arrays of directions, and its χ² proof (sampling/check.h).
#include <fmt/format.h>
#include <pybind11/stl.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "binding.h"
#include "specula/sampling/check.h"

namespace specula::python {

namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

const sampling::Sampler& sampler_of(const PyModel& m) {
  if (!m.sampler) m.sampler = std::make_shared<const sampling::Sampler>(m.model);
  return *m.sampler;
}

std::size_t row_count(const Rows& a, const char* name, py::ssize_t columns) {
  if (columns == 3 ? a.ndim() != 2 || a.shape(1) != 3 : a.ndim() != 1)
    throw InvalidField(name, columns == 3 ? fmt::format("{} must be an array of 3-vectors, shape (..., 3)", name)
                                          : fmt::format("{} must be an array of numbers", name));
  return static_cast<std::size_t>(a.shape(0));
}

/// Row i of a (count, 3) array as a unit vector; nullopt when it has no direction (zero length,
/// inf or NaN).
std::optional<Vec3> unit_row(const double* rows, std::size_t i) {
  const Vec3 v{rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
  const double length = std::sqrt(dot(v, v));
  if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
  return v * (1 / length);
}

/// Rows in parallel (the sampler is read-only), the GIL released.
template <class Body>
void for_rows(std::size_t count, const Body& body) {
  const py::gil_scoped_release release;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) body(i);
  });
}

py::tuple sample_rows(const PyModel& m, const Rows& wi, const Rows& u1, const Rows& u2) {
  const std::size_t count = row_count(wi, "wi", 3);
  if (row_count(u1, "u1", 1) != count || row_count(u2, "u2", 1) != count)
    throw InvalidField("u1", "wi, u1 and u2 must hold as many values");
  for (const auto& [u, name] : {std::pair{&u1, "u1"}, std::pair{&u2, "u2"}})
    for (std::size_t i = 0; i < count; ++i)
      if (!(u->data()[i] >= 0 && u->data()[i] < 1))
        throw InvalidField(name, fmt::format("{} must be in [0, 1), got {} at index {}", name, u->data()[i], i));
  const sampling::Sampler& sampler = sampler_of(m);
  py::array_t<double> wo({static_cast<py::ssize_t>(count), py::ssize_t{3}});
  py::array_t<double> pdf(static_cast<py::ssize_t>(count)), weight(static_cast<py::ssize_t>(count));
  double* wo_out = wo.mutable_data();
  double* pdf_out = pdf.mutable_data();
  double* weight_out = weight.mutable_data();
  const double *wi_in = wi.data(), *u1_in = u1.data(), *u2_in = u2.data();
  for_rows(count, [&](std::size_t i) {
    const std::optional<Vec3> w = unit_row(wi_in, i);
    const sampling::Sample s = w && w->z > 0 ? sampler.sample(*w, u1_in[i], u2_in[i]) : sampling::Sample{};
    wo_out[3 * i] = s.wo.x, wo_out[3 * i + 1] = s.wo.y, wo_out[3 * i + 2] = s.wo.z;
    pdf_out[i] = s.pdf;
    weight_out[i] = s.weight;
  });
  return py::make_tuple(wo, pdf, weight);
}

py::array_t<double> pdf_rows(const PyModel& m, const Rows& wi, const Rows& wo) {
  const std::size_t count = row_count(wi, "wi", 3);
  if (row_count(wo, "wo", 3) != count) throw InvalidField("wo", "wi and wo must hold as many directions");
  const sampling::Sampler& sampler = sampler_of(m);
  py::array_t<double> pdf(static_cast<py::ssize_t>(count));
  double* out = pdf.mutable_data();
  const double *wi_in = wi.data(), *wo_in = wo.data();
  for_rows(count, [&](std::size_t i) {
    const std::optional<Vec3> a = unit_row(wi_in, i), b = unit_row(wo_in, i);
    out[i] = a && b && a->z > 0 ? sampler.pdf(*a, *b) : 0.0;
  });
  return pdf;
}

py::dict angle_dict(const sampling::AngleCheck& a) {
  py::dict d;
  d["theta_deg"] = a.theta_deg;
  d["samples"] = a.valid_samples;
  d["chi2"] = a.chi2;
  d["dof"] = a.dof;
  d["p_value"] = a.p_value;
  d["alpha"] = a.alpha;
  d["pdf_integral"] = a.pdf_integral;
  d["mean_weight"] = a.mean_weight;
  d["standard_error"] = a.standard_error;
  d["albedo"] = a.albedo;
  d["max_weight"] = a.max_weight;
  d["outside"] = a.outside;
  d["weight_mismatches"] = a.weight_mismatches;
  d["uncovered"] = a.uncovered_nodes;
  d["in_empty_cells"] = a.unexpected_samples;
  d["negative"] = a.negative_samples;
  d["min_f"] = a.min_f;
  d["non_finite"] = a.non_finite_samples;
  d["passes"] = a.passes();
  const auto grid = [](const std::vector<double>& v) {
    py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), out.mutable_data());
    return out;
  };
  d["observed"] = grid(a.observed);
  d["expected"] = grid(a.expected);
  return d;
}

py::dict check_sampling(const py::object& model, const py::object& theta, std::size_t samples, std::uint64_t seed,
                          int bins, double alpha) {
  std::optional<PyModel> storage;
  const PyModel& m = model_argument(model, storage);
  sampling::SamplingCheckOptions options;
  options.theta_deg = values_of(theta, "theta");
  if (options.theta_deg.empty() || options.theta_deg.size() > sampling::kMaxSamplingAngles)
    throw InvalidField("theta", fmt::format("theta: 1 to {} angles, got {}", sampling::kMaxSamplingAngles,
                                            options.theta_deg.size()));
  if (samples > sampling::kMaxSamplingTotal / options.theta_deg.size())
    throw InvalidField("samples", fmt::format("samples {} at {} angles is more than the {} a check may draw", samples,
                                              options.theta_deg.size(), sampling::kMaxSamplingTotal));
  options.samples = samples;
  options.seed = seed;
  options.cos_bins = bins;
  options.alpha = alpha;
  const sampling::SamplingCheck c = run_interruptible([&] {
    return sampling::check_sampling(sampler_of(m), options);
  });
  py::list angles;
  for (const auto& a : c.angles) angles.append(angle_dict(a));
  py::dict out;
  out["passes"] = c.passes();
  out["method"] = c.method;
  out["table_error"] = c.table_error;
  out["bins"] = c.cos_bins;
  out["angles"] = angles;
  return out;
}

}  // namespace

void bind_sampling(py::module_& m, py::class_<PyModel>& model_class) {
  model_class.def("_sample", &sample_rows, py::arg("wi"), py::arg("u1"), py::arg("u2"));
  model_class.def("_pdf", &pdf_rows, py::arg("wi"), py::arg("wo"));
  m.def("_check_sampling", &check_sampling, py::arg("model"), py::arg("theta"), py::arg("samples"), py::arg("seed"),
        py::arg("bins"), py::arg("alpha"));
}

}  // namespace specula::python
