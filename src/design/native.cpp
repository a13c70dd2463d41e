#include "native.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <dlfcn.h>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <unistd.h>
#include <unordered_set>

#include "process.h"
#include "specula/exceptions.h"

namespace specula::design {

using expr::Node;
using expr::Op;

namespace {


// A value of the formula while it is written out: a uniform (a scalar C++ expression of numbers
// and the parameter p) or a vector expression in x (the cosine's lanes).
struct Value {
  Value(bool is_uniform, std::string value_text, bool reads = false)
      : uniform(is_uniform), reads_param(reads), text(std::move(value_text)) {}
  bool uniform = true;
  bool reads_param = false;  // a uniform of p (computed once per material), else of numbers alone
  std::string text;
  std::string mul_left, mul_right;  // set when the vector text is hn::Mul(left, right)
};

// A double literal (never an integer one: 14 / 9 is not 1).
std::string literal(double v) {
  std::string text = fmt::format("{:.17g}", v);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string scalar_call(Op op, const std::string& a) {
  return fmt::format("std::{}({})", expr::function_name(op), a);
}

std::string scalar_text(Op op, const Value& a, const Value* b) {
  switch (op) {
    case Op::add: return "(" + a.text + " + " + b->text + ")";
    case Op::sub: return "(" + a.text + " - " + b->text + ")";
    case Op::mul: return "(" + a.text + " * " + b->text + ")";
    case Op::div: return "(" + a.text + " / " + b->text + ")";
    case Op::pow: return "std::pow(" + a.text + ", " + b->text + ")";
    case Op::min: return "std::fmin(" + a.text + ", " + b->text + ")";
    case Op::max: return "std::fmax(" + a.text + ", " + b->text + ")";
    case Op::neg: return "(-" + a.text + ")";
    case Op::constant:
    case Op::variable: break;
    default: return scalar_call(op, a.text);
  }
  unreachable();
}

Value scalar(Op op, const Value& a, const Value* b) {
  return {true, scalar_text(op, a, b), a.reads_param || (b && b->reads_param)};
}

class Writer {
 public:
  Writer(std::size_t index, std::size_t variables) : index_(index), variables_(variables) {}

  std::size_t uniform_count() const { return uniforms_.size(); }

  // The function's text; `operations` counts its vector operations.
  std::string function(const expr::Expression& formula, int& operations) {
    std::vector<Value> stack;
    for (const Node& n : formula.nodes()) {
      switch (expr::arity(n.op)) {
        case 0:
          stack.push_back(n.op == Op::constant  ? Value{true, literal(n.value)}
                          : n.var < variables_ ? Value{false, variables_ == 1 ? std::string("x") : fmt::format("x{}", n.var)}
                                                : Value{true, "p", true});
          break;
        case 1: {
          Value a = std::move(stack.back());
          stack.back() = apply(n.op, a, nullptr);
          break;
        }
        default: {
          Value b = std::move(stack.back());
          stack.pop_back();
          Value a = std::move(stack.back());
          stack.back() = apply(n.op, a, &b);
        }
      }
    }
    operations = operations_;
    Value result = stack.back();
    if (result.uniform) result.text = vector_of(result);
    if (variables_ > 1) return several_variables(result.text);
    std::string out = uniforms_function() + fmt::format(
        "extern \"C\" void specula_lobe_{}(const float* c, float* out, std::size_t count, const float* u) {{\n"
        "  const hn::ScalableTag<float> d;\n"
        "  const auto zero = hn::Zero(d);\n"
        "  const auto one = hn::Set(d, 1.0f);\n",
        index_) + uniform_loads();
    out += fmt::format(
        "  const auto lobe = [&](hn::Vec<decltype(d)> c_lanes) {{\n"
        "    const auto x = hn::Min(c_lanes, one);\n"
        "    return hn::IfThenZeroElse(hn::Le(c_lanes, zero), {});\n"
        "  }};\n"
        "  const std::size_t lanes = hn::Lanes(d);\n"
        "  std::size_t i = 0;\n"
        "  for (; i + lanes <= count; i += lanes) hn::StoreU(lobe(hn::LoadU(d, c + i)), d, out + i);\n"
        "  if (i < count) {{\n"
        "    alignas(64) float in[64] = {{}}, result[64];\n"
        "    for (std::size_t k = i; k < count; ++k) in[k - i] = c[k];\n"
        "    hn::Store(lobe(hn::Load(d, in)), d, result);\n"
        "    for (std::size_t k = i; k < count; ++k) out[k] = result[k - i];\n"
        "  }}\n"
        "  (void)u;\n"
        "}}\n",
        result.text);
    return out;
  }

 private:
  // A uniform as lanes: a number the compiler sees (folded, and the same number shared), or one
  // of the material's uniforms (each distinct text once).
  std::string vector_of(const Value& v) {
    if (!v.uniform) return v.text;
    if (!v.reads_param) return fmt::format("hn::Set(d, static_cast<float>({}))", v.text);
    const auto found = std::ranges::find(uniforms_, v.text);
    if (found != uniforms_.end()) return fmt::format("u{}", found - uniforms_.begin());
    uniforms_.push_back(v.text);
    return fmt::format("u{}", uniforms_.size() - 1);
  }

  // The uniforms' function, run once per material (not timed), and their loads at the kernel's top.
  std::string uniforms_function() const {
    std::string out = fmt::format("extern \"C\" void specula_uniforms_{}(double p, float* u) {{\n", index_);
    for (std::size_t j = 0; j < uniforms_.size(); ++j) out += fmt::format("  u[{}] = static_cast<float>({});\n", j, uniforms_[j]);
    return out + "  (void)p;\n  (void)u;\n}\n";
  }
  std::string uniform_loads() const {
    std::string out;
    for (std::size_t j = 0; j < uniforms_.size(); ++j) out += fmt::format("  const auto u{} = hn::Set(d, u[{}]);\n", j, j);
    return out;
  }

  // An operation on lanes, counted once however often it appears (the compiler computes it once).
  Value vector(std::string text) {
    if (counted_.insert(text).second) ++operations_;
    return {false, std::move(text)};
  }

  // An FMA in place of the product it absorbs (counted already).
  Value fused(std::string text) {
    if (!counted_.contains(text)) --operations_;
    return vector(std::move(text));
  }

  // x^k for an integer k, 1 ≤ k ≤ 32, by squaring.
  Value power(const std::string& x, int k) {
    std::string result, square = x;
    for (; k > 0; k >>= 1) {
      if (k & 1) result = result.empty() ? square : vector("hn::Mul(" + result + ", " + square + ")").text;
      if (k > 1) square = vector("hn::Mul(" + square + ", " + square + ")").text;
    }
    return {false, result};
  }

  Value apply(Op op, const Value& a, const Value* b) {
    if (a.uniform && (!b || b->uniform)) return scalar(op, a, b);
    if (op == Op::pow && b->uniform) {
      char* end = nullptr;
      const double k = std::strtod(b->text.c_str(), &end);
      if (end && *end == 0 && k == std::round(k) && k >= 1 && k <= 32) return power(a.text, static_cast<int>(k));
    }
    if (op == Op::add) {  // a·u + v as one FMA
      if (!a.mul_left.empty()) return fused(fmt::format("hn::MulAdd({}, {}, {})", a.mul_left, a.mul_right, vector_of(*b)));
      if (!b->mul_left.empty()) return fused(fmt::format("hn::MulAdd({}, {}, {})", b->mul_left, b->mul_right, vector_of(a)));
    }
    if (op == Op::sub) {  // a·u − v and v − a·u as one FMA
      if (!a.mul_left.empty()) return fused(fmt::format("hn::MulSub({}, {}, {})", a.mul_left, a.mul_right, vector_of(*b)));
      if (!b->mul_left.empty()) return fused(fmt::format("hn::NegMulAdd({}, {}, {})", b->mul_left, b->mul_right, vector_of(a)));
    }
    const std::string x = vector_of(a);
    const std::string y = b ? vector_of(*b) : "";
    switch (op) {
      case Op::add: return vector("hn::Add(" + x + ", " + y + ")");
      case Op::sub: return vector("hn::Sub(" + x + ", " + y + ")");
      case Op::mul: {
        Value v = vector("hn::Mul(" + x + ", " + y + ")");
        v.mul_left = x;
        v.mul_right = y;
        return v;
      }
      case Op::div: return vector("hn::Div(" + x + ", " + y + ")");
      case Op::min: return vector("hn::Min(" + x + ", " + y + ")");
      case Op::max: return vector("hn::Max(" + x + ", " + y + ")");
      case Op::pow: return vector("hn::Exp(d, hn::Mul(" + y + ", hn::Log(d, " + x + ")))");
      case Op::neg: return vector("hn::Neg(" + x + ")");
      case Op::abs: return vector("hn::Abs(" + x + ")");
      case Op::sqrt: return vector("hn::Sqrt(" + x + ")");
      case Op::exp: return vector("hn::Exp(d, " + x + ")");
      case Op::log: return vector("hn::Log(d, " + x + ")");
      case Op::log2: return vector("hn::Log2(d, " + x + ")");
      case Op::expm1: return vector("hn::Expm1(d, " + x + ")");
      case Op::log1p: return vector("hn::Log1p(d, " + x + ")");
      case Op::sin: return vector("hn::Sin(d, " + x + ")");
      case Op::cos: return vector("hn::Cos(d, " + x + ")");
      case Op::acos: return vector("hn::Acos(d, " + x + ")");
      case Op::asin: return vector("hn::Asin(d, " + x + ")");
      case Op::constant:
      case Op::variable: break;
    }
    unreachable();
  }

  // A function of several per-pixel variables: one input array each (in[v]), each clamped to 1
  // and the value 0 where one is ≤ 0, as for one variable.
  std::string several_variables(const std::string& result) {
    std::string out = uniforms_function() + fmt::format(
        "extern \"C\" void specula_lobe_{}(const float* const* in, float* out, std::size_t count, const float* u) {{\n"
        "  const hn::ScalableTag<float> d;\n"
        "  const auto zero = hn::Zero(d);\n"
        "  const auto one = hn::Set(d, 1.0f);\n",
        index_) + uniform_loads();
    std::string parameters, clamps, outside;
    for (std::size_t v = 0; v < variables_; ++v) {
      parameters += fmt::format("{}hn::Vec<decltype(d)> v{}", v ? ", " : "", v);
      clamps += fmt::format("    const auto x{} = hn::Min(v{}, one);\n", v, v);
      outside += v ? fmt::format(", hn::Le(v{}, zero))", v) : "hn::Le(v0, zero)";
      if (v) outside = "hn::Or(" + outside;
    }
    std::string loads, tail_loads, tail_fill;
    for (std::size_t v = 0; v < variables_; ++v) {
      loads += fmt::format("{}hn::LoadU(d, in[{}] + i)", v ? ", " : "", v);
      tail_loads += fmt::format("{}hn::Load(d, tail[{}])", v ? ", " : "", v);
      tail_fill += fmt::format("    for (std::size_t k = i; k < count; ++k) tail[{}][k - i] = in[{}][k];\n", v, v);
    }
    out += fmt::format(
        "  const auto lobe = [&]({}) {{\n{}"
        "    return hn::IfThenZeroElse({}, {});\n"
        "  }};\n"
        "  const std::size_t lanes = hn::Lanes(d);\n"
        "  std::size_t i = 0;\n"
        "  for (; i + lanes <= count; i += lanes) hn::StoreU(lobe({}), d, out + i);\n"
        "  if (i < count) {{\n"
        "    alignas(64) float tail[{}][64] = {{}}, result[64];\n{}"
        "    hn::Store(lobe({}), d, result);\n"
        "    for (std::size_t k = i; k < count; ++k) out[k] = result[k - i];\n"
        "  }}\n"
        "  (void)u;\n"
        "}}\n",
        parameters, clamps, outside, result, loads, variables_, tail_fill, tail_loads);
    return out;
  }

  std::size_t index_, variables_;
  int operations_ = 0;
  std::unordered_set<std::string> counted_;  // the operations counted
  std::vector<std::string> uniforms_;
};

}  // namespace

NativeSource native_source(const std::vector<NativeLobe>& lobes) {
  NativeSource out;
  out.text =
      "// Generated by specula design: the designed lobes as Highway kernels in float lanes.\n"
      "#include <cmath>\n#include <cstddef>\n"
      "#include \"hwy/highway.h\"\n#include \"hwy/contrib/math/math-inl.h\"\n"
      "namespace hn = hwy::HWY_NAMESPACE;\n\n";
  for (std::size_t i = 0; i < lobes.size(); ++i) {
    int operations = 0;
    Writer writer(i, lobes[i].variables);
    out.text += writer.function(lobes[i].formula, operations) + "\n";
    out.operations.push_back(operations);
    out.uniforms.push_back(writer.uniform_count());
  }
  return out;
}

std::string native_compiler() {
  const char* chosen = std::getenv("SPECULA_CXX");
  if (!chosen || !*chosen) return find_executable(SPECULA_CXX).string();
  const auto found = find_executable(chosen);
  if (found.empty())
    throw InvalidArgument(fmt::format("SPECULA_CXX names '{}', which is not an executable file{}", chosen,
                                      std::string_view(chosen).find('/') == std::string_view::npos ? " in PATH" : ""));
  return found.string();
}

std::chrono::seconds compile_limit() {
  const char* text = std::getenv("SPECULA_COMPILE_TIMEOUT");
  if (!text || !*text) return kDefaultCompileLimit;
  const std::string_view value(text);
  int seconds = 0;
  const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), seconds);
  if (error != std::errc{} || end != value.data() + value.size() || seconds < 1 || seconds > kMaxCompileLimit.count())
    throw InvalidArgument(fmt::format("SPECULA_COMPILE_TIMEOUT must be a whole number of seconds in [1, {}], got '{}'",
                                      kMaxCompileLimit.count(), value));
  return std::chrono::seconds(seconds);
}

NativeKernels::NativeKernels(const std::vector<NativeLobe>& lobes, const std::filesystem::path& work_dir,
                             const std::function<bool()>& stop) {
  const std::string compiler = native_compiler();
  if (compiler.empty()) throw std::runtime_error("no C++ compiler found (SPECULA_CXX unset, and no " SPECULA_CXX ")");
  const NativeSource source = native_source(lobes);
  const auto cpp = work_dir / "lobes.cpp", so = work_dir / "lobes.so", log = work_dir / "compile.log";
  std::ofstream(cpp) << source.text;
  // The kernels use Highway's static target only (no dynamic dispatch: they run where they are
  // built). HWY_COMPILE_ONLY_STATIC says so to Highway, whose target detection otherwise stops
  // with an #error when -march=native enables a target it leaves out of the dynamic set (Debian
  // 12's Highway 1.0.3 on AVX-512 CPUs with VBMI2/VNNI/BITALG, e.g. AMD Zen 4).
  const int status = run_process({compiler, "-std=gnu++20", "-O2", "-march=native", "-DHWY_COMPILE_ONLY_STATIC=1",
                                  "-fPIC", "-shared", "-o", so.string(), cpp.string()},
                                 log, stop, compile_limit());
  if (status != 0) throw std::runtime_error(fmt::format("compiling the kernels failed: {}", first_error(log)));
  library_ = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library_) throw std::runtime_error(fmt::format("loading the kernels failed: {}", dlerror()));
  using Uniforms = void (*)(double, float*);
  using Function = void (*)(const float*, float*, std::size_t, const float*);
  using Several = void (*)(const float* const*, float*, std::size_t, const float*);
  for (std::size_t i = 0; i < lobes.size(); ++i) {
    void* symbol = dlsym(library_, fmt::format("specula_lobe_{}", i).c_str());
    void* uniforms_symbol = dlsym(library_, fmt::format("specula_uniforms_{}", i).c_str());
    if (!symbol || !uniforms_symbol) throw std::runtime_error("a kernel is missing from the compiled library");
    // The per-material constants, once (a renderer's uniforms): the timed work is per pixel only.
    auto uniforms = std::make_shared<std::vector<float>>(std::max<std::size_t>(source.uniforms[i], 1));
    reinterpret_cast<Uniforms>(uniforms_symbol)(lobes[i].param, uniforms->data());
    if (lobes[i].variables == 1) {
      kernels_.push_back([f = reinterpret_cast<Function>(symbol), uniforms](std::span<const float> c, std::span<float> out) {
        f(c.data(), out.data(), std::min(c.size(), out.size()), uniforms->data());
      });
      continue;
    }
    // The other variables' inputs are made from the cosines once per span (the harness calls the
    // kernel again and again on the same one): the timed work is the kernel's alone.
    auto inputs = std::make_shared<VariableInputs>(lobes[i].variables);
    kernels_.push_back([f = reinterpret_cast<Several>(symbol), uniforms, inputs](std::span<const float> c, std::span<float> out) {
      f(inputs->of(c).data(), out.data(), std::min(c.size(), out.size()), uniforms->data());
    });
  }
  operations_ = source.operations;
}

NativeKernels::~NativeKernels() {
  kernels_.clear();
  if (library_) dlclose(library_);
}

const std::vector<const float*>& VariableInputs::of(std::span<const float> c) {
  if (c.data() != source_ || c.size() != size_) {
    source_ = c.data();
    size_ = c.size();
    values_.assign(pointers_.size(), std::vector<float>(c.size()));
    for (std::size_t v = 0; v < pointers_.size(); ++v) {
      for (std::size_t i = 0; i < c.size(); ++i) values_[v][i] = variable_value(c, i, v, pointers_.size());
      pointers_[v] = values_[v].data();
    }
  }
  return pointers_;
}

double kernel_deviation(const cost::FloatKernel& kernel, const NativeLobe& lobe) {
  constexpr std::size_t kPoints = 4099;
  std::vector<float> c(kPoints), out(kPoints);
  for (std::size_t i = 0; i < kPoints; ++i) c[i] = static_cast<float>(static_cast<double>(i) / (kPoints - 1));
  kernel(c, out);
  double worst = 0;
  std::vector<double> x(lobe.variables + 1, lobe.param);
  for (std::size_t i = 0; i < kPoints; ++i) {
    bool outside = false;
    for (std::size_t v = 0; v < lobe.variables; ++v) {
      x[v] = static_cast<double>(variable_value(c, i, v, lobe.variables));
      outside |= x[v] <= 0;
    }
    const double expected = outside ? 0 : expr::evaluate(lobe.formula, x);
    const double d = std::abs(static_cast<double>(out[i]) - expected);
    if (std::isfinite(expected)) worst = std::max(worst, std::isnan(d) ? INFINITY : d);
  }
  return worst;
}

}  // namespace specula::design
