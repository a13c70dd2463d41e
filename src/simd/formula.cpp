// The vectorized formula path (include/specula/simd/formula.h): per chunk of rows, each step of
// the program runs its postfix nodes over columns, one Highway loop per node. An operand is a
// column of the chunk or one value for every row (a constant, a parameter, or a result of only
// such): ops on uniform operands run once, on a broadcast vector, so a formula's constant parts
// (a² of GGX, 1/ln 2) cost nothing per row and round as the vector op rounds them.
#include <algorithm>
#include <array>
#include <cstddef>

#include "specula/exceptions.h"
#include "specula/simd/formula.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/simd/formula.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/aligned_allocator.h"
#include "hwy/highway.h"
#include "src/simd/formula_ops-inl.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {

using expr::Op;

/// An operand: a column of the chunk, or (data == nullptr) `value` in every row.
template <class T>
struct Operand {
  const T* data = nullptr;
  T value = 0;
};

/// out = f(a) over `rows` (a multiple of the lanes); a uniform a gives a uniform result.
template <class D, class F>
HWY_INLINE Operand<hn::TFromD<D>> Map1(D d, const Operand<hn::TFromD<D>>& a, hn::TFromD<D>* out,
                                      std::size_t rows, const F& f) {
  if (!a.data) return {nullptr, hn::GetLane(f(hn::Set(d, a.value)))};
  for (std::size_t i = 0; i < rows; i += hn::Lanes(d)) hn::Store(f(hn::Load(d, a.data + i)), d, out + i);
  return {out};
}

/// out = f(a, b) over `rows`, a uniform operand broadcast once.
template <class D, class F>
HWY_INLINE Operand<hn::TFromD<D>> Map2(D d, const Operand<hn::TFromD<D>>& a, const Operand<hn::TFromD<D>>& b,
                                      hn::TFromD<D>* out, std::size_t rows, const F& f) {
  const std::size_t lanes = hn::Lanes(d);
  if (!a.data && !b.data) return {nullptr, hn::GetLane(f(hn::Set(d, a.value), hn::Set(d, b.value)))};
  if (!b.data) {
    const V<D> vb = hn::Set(d, b.value);
    for (std::size_t i = 0; i < rows; i += lanes) hn::Store(f(hn::Load(d, a.data + i), vb), d, out + i);
  } else if (!a.data) {
    const V<D> va = hn::Set(d, a.value);
    for (std::size_t i = 0; i < rows; i += lanes) hn::Store(f(va, hn::Load(d, b.data + i)), d, out + i);
  } else {
    for (std::size_t i = 0; i < rows; i += lanes)
      hn::Store(f(hn::Load(d, a.data + i), hn::Load(d, b.data + i)), d, out + i);
  }
  return {out};
}

template <class D>
Operand<hn::TFromD<D>> Unary(D d, Op op, const Operand<hn::TFromD<D>>& a, hn::TFromD<D>* out, std::size_t rows) {
  auto map = [&](const auto& f) { return Map1(d, a, out, rows, f); };
  switch (op) {
    case Op::neg: return map([](V<D> x) { return hn::Neg(x); });
    case Op::abs: return map([](V<D> x) { return hn::Abs(x); });
    case Op::sqrt: return map([](V<D> x) { return hn::Sqrt(x); });
    case Op::log: return map([d](V<D> x) { return LogOp(d, x); });
    case Op::log2: return map([d](V<D> x) { return Log2Op(d, x); });
    case Op::exp: return map([d](V<D> x) { return ExpOp(d, x); });
    case Op::expm1: return map([d](V<D> x) { return Expm1Op(d, x); });
    case Op::log1p: return map([d](V<D> x) { return Log1pOp(d, x); });
    case Op::sin: return map([d](V<D> x) { return SinOp(d, x); });
    case Op::cos: return map([d](V<D> x) { return CosOp(d, x); });
    case Op::acos: return map([d](V<D> x) { return AcosOp(d, x); });
    case Op::asin: return map([d](V<D> x) { return AsinOp(d, x); });
    case Op::constant:
    case Op::variable:
    case Op::add:
    case Op::sub:
    case Op::mul:
    case Op::div:
    case Op::pow:
    case Op::min:
    case Op::max: break;  // not unary: RunStep sends them elsewhere
  }
  unreachable();
}

/// pow with a uniform integral exponent small enough for the multiplication chain, or PowOp.
template <class D>
Operand<hn::TFromD<D>> Power(D d, const Operand<hn::TFromD<D>>& a, const Operand<hn::TFromD<D>>& b,
                             hn::TFromD<D>* out, std::size_t rows) {
  using T = hn::TFromD<D>;
  constexpr int kMax = kMaxPowChain<T>;
  if (!b.data && b.value == std::round(b.value) && std::abs(b.value) <= T(kMax)) {
    const int k = static_cast<int>(b.value);
    return Map1(d, a, out, rows, [d, k](V<D> x) { return PowInteger(d, x, k); });
  }
  return Map2(d, a, b, out, rows, [d](V<D> x, V<D> y) { return PowOp(d, x, y); });
}

template <class D>
Operand<hn::TFromD<D>> Binary(D d, Op op, const Operand<hn::TFromD<D>>& a, const Operand<hn::TFromD<D>>& b,
                              hn::TFromD<D>* out, std::size_t rows) {
  auto map = [&](const auto& f) { return Map2(d, a, b, out, rows, f); };
  switch (op) {
    case Op::add: return map([](V<D> x, V<D> y) { return hn::Add(x, y); });
    case Op::sub: return map([](V<D> x, V<D> y) { return hn::Sub(x, y); });
    case Op::mul: return map([](V<D> x, V<D> y) { return hn::Mul(x, y); });
    case Op::div: return map([](V<D> x, V<D> y) { return hn::Div(x, y); });
    case Op::min: return map([](V<D> x, V<D> y) { return MinOp<D>(x, y); });
    case Op::max: return map([](V<D> x, V<D> y) { return MaxOp<D>(x, y); });
    case Op::pow: return Power(d, a, b, out, rows);
    case Op::constant:
    case Op::variable:
    case Op::neg:
    case Op::log:
    case Op::log2:
    case Op::exp:
    case Op::sqrt:
    case Op::abs:
    case Op::sin:
    case Op::cos:
    case Op::acos:
    case Op::expm1:
    case Op::log1p:
    case Op::asin: break;  // not binary: RunStep sends them elsewhere
  }
  unreachable();
}

/// One step over the chunk: the stack's level k writes column stack + k·kFormulaRows.
template <class D>
Operand<hn::TFromD<D>> RunStep(D d, const expr::Expression& e, const Operand<hn::TFromD<D>>* slots,
                               hn::TFromD<D>* stack, std::size_t rows) {
  using T = hn::TFromD<D>;
  std::array<Operand<T>, expr::kMaxFormulaDepth> top;
  std::size_t depth = 0;
  for (const expr::Node& node : e.nodes()) {
    if (node.op == Op::constant) {
      top[depth++] = {nullptr, static_cast<T>(node.value)};
    } else if (node.op == Op::variable) {
      top[depth++] = slots[node.var];
    } else if (expr::arity(node.op) == 1) {
      top[depth - 1] = Unary(d, node.op, top[depth - 1], stack + (depth - 1) * kFormulaRows, rows);
    } else {
      --depth;
      top[depth - 1] = Binary(d, node.op, top[depth - 1], top[depth], stack + (depth - 1) * kFormulaRows, rows);
    }
  }
  return top[0];
}

/// The columns a program needs per chunk: its inputs, its lets and its deepest stack.
template <class T>
struct ChunkColumns {
  explicit ChunkColumns(const expr::Program& p) {
    std::size_t depth = p.result().stack_depth();
    for (const auto& step : p.lets()) depth = std::max(depth, step.stack_depth());
    storage = hwy::AllocateAligned<T>((p.input_count() + p.lets().size() + depth) * kFormulaRows);
    stack = storage.get() + (p.input_count() + p.lets().size()) * kFormulaRows;
  }
  T* input(std::size_t i) { return storage.get() + i * kFormulaRows; }

  hwy::AlignedFreeUniquePtr<T[]> storage;
  T* stack = nullptr;
};

/// Runs `program` chunk by chunk over `count` rows: fill(first, n, columns) writes the n rows
/// of each input column (padded to whole vectors by RunProgram), emit(first, n, result) takes
/// the result.
template <class D, class Fill, class Emit>
void RunProgram(D d, const expr::Program& program, std::span<const double> params, std::size_t count,
                const Fill& fill, const Emit& emit) {
  using T = hn::TFromD<D>;
  ChunkColumns<T> columns(program);
  std::array<Operand<T>, expr::kMaxSlots> slots;
  const std::size_t inputs = program.input_count(), first_let = inputs + program.param_count();
  for (std::size_t i = 0; i < inputs; ++i) slots[i] = {columns.input(i)};
  for (std::size_t p = 0; p < params.size(); ++p) slots[inputs + p] = {nullptr, static_cast<T>(params[p])};
  const std::size_t lanes = hn::Lanes(d);
  for (std::size_t first = 0; first < count; first += kFormulaRows) {
    const std::size_t n = std::min(kFormulaRows, count - first), rows = (n + lanes - 1) / lanes * lanes;
    fill(first, n, columns);
    for (std::size_t i = 0; i < inputs; ++i) std::fill(columns.input(i) + n, columns.input(i) + rows, T(1));
    for (std::size_t k = 0; k < program.lets().size(); ++k) {
      T* let_column = columns.input(inputs + k);
      const Operand<T> value = RunStep(d, program.lets()[k], slots.data(), columns.stack, rows);
      if (value.data) std::copy_n(value.data, rows, let_column);
      slots[first_let + k] = value.data ? Operand<T>{let_column} : value;
    }
    emit(first, n, RunStep(d, program.result(), slots.data(), columns.stack, rows));
  }
}

/// The program over whole input arrays of TIn in the lanes of D (each row copied in, rounded out).
template <class D, class TIn>
void RunColumns(D d, const expr::Program& program, const std::span<const TIn>* inputs, std::span<const double> params,
                std::size_t count, TIn* out) {
  using T = hn::TFromD<D>;
  auto fill = [&](std::size_t first, std::size_t n, ChunkColumns<T>& columns) {
    for (std::size_t i = 0; i < program.input_count(); ++i)
      std::transform(inputs[i].data() + first, inputs[i].data() + first + n, columns.input(i),
                     [](TIn v) { return static_cast<T>(v); });
  };
  auto emit = [&](std::size_t first, std::size_t n, const Operand<T>& r) {
    for (std::size_t i = 0; i < n; ++i) out[first + i] = static_cast<TIn>(r.data ? r.data[i] : r.value);
  };
  RunProgram(d, program, params, count, fill, emit);
}

void EvalProgramF64(const expr::Program& program, const std::span<const double>* inputs, std::span<const double> params,
                    std::size_t count, double* out) {
  RunColumns(hn::ScalableTag<double>(), program, inputs, params, count, out);
}

void EvalProgramF32(const expr::Program& program, Tier tier, const std::span<const float>* inputs,
                    std::span<const double> params, std::size_t count, float* out) {
  if (tier == Tier::fast) return RunColumns(hn::ScalableTag<float>(), program, inputs, params, count, out);
  RunColumns(hn::ScalableTag<double>(), program, inputs, params, count, out);
}

/// A lobe formula over arrays of TIn in the lanes of D: c clamped to (0, 1] (1 where c ≤ 0 or
/// NaN), u = −ln c where read, then F, then 0 for c ≤ 0 and NaN for NaN (lobes::Formula's rules).
template <class D, class TIn>
void RunFormula(D d, const lobes::Formula& lobe, const TIn* c, std::size_t count, TIn* out) {
  using T = hn::TFromD<D>;
  const auto& definition = lobe.definition();
  const expr::Program& program = definition.in_cos ? *definition.in_cos : *definition.in_log_cos;
  const bool reads_u = program.reads(1);
  const std::size_t lanes = hn::Lanes(d);
  auto fill = [&](std::size_t first, std::size_t n, ChunkColumns<T>& columns) {
    T* cs = columns.input(0);
    for (std::size_t i = 0; i < n; ++i) cs[i] = static_cast<T>(c[first + i]);
    std::fill(cs + n, cs + (n + lanes - 1) / lanes * lanes, T(1));
    for (std::size_t i = 0; i < n; i += lanes) {
      const V<D> v = hn::Load(d, cs + i), one = hn::Set(d, T(1));
      const V<D> clamped = hn::IfThenElse(hn::Gt(v, hn::Zero(d)), hn::Min(v, one), one);
      hn::Store(clamped, d, cs + i);
      if (reads_u) hn::Store(hn::Neg(LogOp(d, clamped)), d, columns.input(1) + i);
    }
  };
  auto emit = [&](std::size_t first, std::size_t n, const Operand<T>& r) {
    for (std::size_t i = 0; i < n; ++i) {
      const TIn ci = c[first + i];
      const TIn f = static_cast<TIn>(r.data ? r.data[i] : r.value);
      out[first + i] = ci > 0 ? f : (std::isnan(ci) ? ci : TIn(0));
    }
  };
  RunProgram(d, program, lobe.params(), count, fill, emit);
}

void EvalFormulaF32(const lobes::Formula& lobe, Tier tier, const float* c, std::size_t count, float* out) {
  if (tier == Tier::fast) return RunFormula(hn::ScalableTag<float>(), lobe, c, count, out);
  RunFormula(hn::ScalableTag<double>(), lobe, c, count, out);
}

void EvalFormulaF64(const lobes::Formula& lobe, const double* c, std::size_t count, double* out) {
  RunFormula(hn::ScalableTag<double>(), lobe, c, count, out);
}

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::simd {

HWY_EXPORT(EvalProgramF64);
HWY_EXPORT(EvalProgramF32);
HWY_EXPORT(EvalFormulaF32);
HWY_EXPORT(EvalFormulaF64);

void eval_program(const expr::Program& program, std::span<const std::span<const double>> inputs,
                  std::span<const double> params, std::span<double> out) {
  HWY_DYNAMIC_DISPATCH(EvalProgramF64)(program, inputs.data(), params, out.size(), out.data());
}

void eval_program(const expr::Program& program, Tier tier, std::span<const std::span<const float>> inputs,
                  std::span<const double> params, std::span<float> out) {
  HWY_DYNAMIC_DISPATCH(EvalProgramF32)(program, tier, inputs.data(), params, out.size(), out.data());
}

void eval_formula(const lobes::Formula& lobe, Tier tier, std::span<const float> c, std::span<float> out) {
  HWY_DYNAMIC_DISPATCH(EvalFormulaF32)(lobe, tier, c.data(), std::min(c.size(), out.size()), out.data());
}

void eval_formula(const lobes::Formula& lobe, Tier, std::span<const double> c, std::span<double> out) {
  HWY_DYNAMIC_DISPATCH(EvalFormulaF64)(lobe, c.data(), std::min(c.size(), out.size()), out.data());
}

}  // namespace specula::simd
#endif
