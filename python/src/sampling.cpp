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

const sampling::Sampler& sampler_of(const PyModel& m) {
  if (!m.sampler) m.sampler = std::make_shared<const sampling::Sampler>(m.model);
  return *m.sampler;
}

/// Row i of a chunk of 3-vectors as a unit vector; nullopt when it has no direction (zero length,
/// inf or NaN).
std::optional<Vec3> unit_row(std::span<const double> rows, std::size_t i) {
  const Vec3 v{rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
  const double length = std::sqrt(dot(v, v));
  if (!(length > 0) || !std::isfinite(length)) return std::nullopt;
  return v * (1 / length);
}

/// Rows [0, count) of a chunk in parallel (the sampler is read-only), in ranges of at least 64 rows
/// (a chunk of costly rows holds a few thousand).
template <class Body>
void parallel_rows(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 64), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) body(i);
  });
}

/// Elements [begin, end) of a uniform number's array, each in [0, 1) (ValueError naming the
/// first that is not, by its index in the whole array).
std::span<const double> uniforms(Elements<double>& u, const char* name, std::size_t begin, std::size_t end) {
  const std::span<const double> values = u.chunk(begin, end);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!(values[i] >= 0 && values[i] < 1))
      throw InvalidField(name, fmt::format("{} must be in [0, 1), got {} at index {}", name, values[i], begin + i));
  return values;
}

py::tuple sample_rows(const PyModel& m, const py::array_t<double>& wi, const py::array_t<double>& u1,
                      const py::array_t<double>& u2) {
  const std::size_t count = vector_count(wi, "wi");
  if (static_cast<std::size_t>(u1.size()) != count || static_cast<std::size_t>(u2.size()) != count)
    throw InvalidField("u1", "wi, u1 and u2 must hold as many values");
  const sampling::Sampler& sampler = sampler_of(m);
  py::array_t<double> wo({static_cast<py::ssize_t>(count), py::ssize_t{3}});
  py::array_t<double> pdf(static_cast<py::ssize_t>(count)), weight(static_cast<py::ssize_t>(count));
  double* wo_out = wo.mutable_data();
  double* pdf_out = pdf.mutable_data();
  double* weight_out = weight.mutable_data();
  Elements<double> directions(wi, py::none()), first(u1, py::none()), second(u2, py::none());
  for_chunks(count, kMaxChunkRows, [&](std::size_t begin, std::size_t end) {
    const std::span<const double> w_in = directions.chunk(3 * begin, 3 * end);
    const std::span<const double> u1_in = uniforms(first, "u1", begin, end), u2_in = uniforms(second, "u2", begin, end);
    parallel_rows(end - begin, [&](std::size_t i) {
      const std::optional<Vec3> w = unit_row(w_in, i);
      const sampling::Sample s = w && w->z > 0 ? sampler.sample(*w, u1_in[i], u2_in[i]) : sampling::Sample{};
      const std::size_t row = begin + i;
      wo_out[3 * row] = s.wo.x, wo_out[3 * row + 1] = s.wo.y, wo_out[3 * row + 2] = s.wo.z;
      pdf_out[row] = s.pdf;
      weight_out[row] = s.weight;
    });
  });
  return py::make_tuple(wo, pdf, weight);
}

py::array_t<double> pdf_rows(const PyModel& m, const py::array_t<double>& wi, const py::array_t<double>& wo) {
  const std::size_t count = vector_count(wi, "wi");
  if (vector_count(wo, "wo") != count) throw InvalidField("wo", "wi and wo must hold as many directions");
  const sampling::Sampler& sampler = sampler_of(m);
  py::array_t<double> pdf(static_cast<py::ssize_t>(count));
  double* out = pdf.mutable_data();
  Elements<double> incoming(wi, py::none()), outgoing(wo, py::none());
  for_chunks(count, kMaxChunkRows, [&](std::size_t begin, std::size_t end) {
    const std::span<const double> wi_in = incoming.chunk(3 * begin, 3 * end);
    const std::span<const double> wo_in = outgoing.chunk(3 * begin, 3 * end);
    parallel_rows(end - begin, [&](std::size_t i) {
      const std::optional<Vec3> a = unit_row(wi_in, i), b = unit_row(wo_in, i);
      out[begin + i] = a && b && a->z > 0 ? sampler.pdf(*a, *b) : 0.0;
    });
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
