// Expression evaluation throughput: expr::evaluate_batch (the postfix stack machine, one chunk
// of rows per node) against a plain recursive interpreter over a pointer tree, row by row.
//
//   BM_ExprBatch/<expression>/rows:R       expr::evaluate_batch over R rows
//   BM_ExprBatchScalarTarget/<expression>/rows:R
//                                          the same on Highway's scalar target (one lane): the
//                                          SIMD gain is BM_ExprBatch's rate over this one's
//   BM_ExprRecursive/<expression>/rows:R   the tree below, evaluated once per row
//
// Expressions: kernel (a fitted 11-node lobe kernel in n), nguyen (x³ + x² + x, 11 nodes) and
// large (31 nodes in n and c with log, exp, sqrt and sin). The label gives the node count.
// items_per_second and node_rows_per_s both count nodes × rows, so they read in node·rows/s.
// Before timing, each benchmark checks that both evaluators agree bit for bit on its inputs.
#include <benchmark/benchmark.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "specula/expr/expr.h"
#include "specula/simd/targets.h"

namespace {

using namespace specula;
using expr::Op;

struct Case {
  const char* label;
  const char* text;
  std::vector<std::string> variables;
};

const Case kCases[] = {
    {"kernel", "0.197254*(n + 1.23891) + 0.0681339/(0.641677 + n)", {"n"}},
    {"nguyen", "x*x*x + x*x + x", {"x"}},
    {"large", "log(1 + n*c) / sqrt(n + 2) + exp(-0.5*c*c) * sin(3*n + c) - 0.25*log(n)",
     {"n", "c"}},
};

struct TreeNode {
  Op op;
  double value;
  unsigned var;
  std::unique_ptr<TreeNode> a, b;
};

std::unique_ptr<TreeNode> build_tree(const expr::Expression& e) {
  std::vector<std::unique_ptr<TreeNode>> stack;
  auto pop = [&] {
    auto top = std::move(stack.back());
    stack.pop_back();
    return top;
  };
  for (const expr::Node& node : e.nodes()) {
    auto tree =
        std::make_unique<TreeNode>(TreeNode{node.op, node.value, node.var, nullptr, nullptr});
    if (expr::arity(node.op) == 2) tree->b = pop();
    if (expr::arity(node.op) >= 1) tree->a = pop();
    stack.push_back(std::move(tree));
  }
  return pop();
}

// The same functions as expr::evaluate, so the results agree bit for bit.
double evaluate_tree(const TreeNode& t, std::span<const std::span<const double>> columns,
                     std::size_t row) {
  const auto a = [&] { return evaluate_tree(*t.a, columns, row); };
  const auto b = [&] { return evaluate_tree(*t.b, columns, row); };
  switch (t.op) {
    case Op::constant: return t.value;
    case Op::variable: return columns[t.var][row];
    case Op::add: return a() + b();
    case Op::sub: return a() - b();
    case Op::mul: return a() * b();
    case Op::div: return a() / b();
    case Op::pow: return std::pow(a(), b());
    case Op::min: {
      const double x = a(), y = b();
      return y < x ? y : x;
    }
    case Op::max: {
      const double x = a(), y = b();
      return x < y ? y : x;
    }
    case Op::neg: return -a();
    case Op::log: return std::log(a());
    case Op::log2: return std::log2(a());
    case Op::exp: return std::exp(a());
    case Op::sqrt: return std::sqrt(a());
    case Op::abs: return std::abs(a());
    case Op::sin: return std::sin(a());
    case Op::cos: return std::cos(a());
    case Op::acos: return std::acos(a());
    case Op::expm1: return std::expm1(a());
    case Op::log1p: return std::log1p(a());
    case Op::asin: return std::asin(a());
  }
  __builtin_unreachable();
}

void evaluate_recursive(const TreeNode& tree, std::span<const std::span<const double>> columns,
                        std::span<double> out) {
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = evaluate_tree(tree, columns, r);
}

// An expression with one column of rows per variable, uniform in [0.5, 8), the same every run.
struct Inputs {
  Inputs(const Case& c, std::size_t rows)
      : e(expr::parse(c.text, c.variables)), data(c.variables.size(), std::vector<double>(rows)) {
    std::mt19937_64 random(42);
    std::uniform_real_distribution<double> uniform(0.5, 8);
    for (auto& column : data) {
      for (double& v : column) v = uniform(random);
      columns.emplace_back(column);
    }
  }
  Inputs(const Inputs&) = delete;  // `columns` points into `data`
  Inputs& operator=(const Inputs&) = delete;

  expr::Expression e;
  std::vector<std::vector<double>> data;
  std::vector<std::span<const double>> columns;
};

bool bit_identical(std::span<const double> x, std::span<const double> y) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::bit_cast<std::uint64_t>(x[i]) != std::bit_cast<std::uint64_t>(y[i])) return false;
  return true;
}

bool evaluators_agree(const Inputs& in, const TreeNode& tree, std::size_t rows) {
  std::vector<double> batch(rows), recursive(rows);
  expr::evaluate_batch(in.e, in.columns, batch);
  evaluate_recursive(tree, in.columns, recursive);
  return bit_identical(batch, recursive);
}

void set_node_rows(benchmark::State& state, const expr::Expression& e, std::size_t rows) {
  const auto node_rows = static_cast<int64_t>(state.iterations()) *
                         static_cast<int64_t>(e.size()) * static_cast<int64_t>(rows);
  state.SetItemsProcessed(node_rows);
  state.counters["node_rows_per_s"] =
      benchmark::Counter(static_cast<double>(node_rows), benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(e.size()) + " nodes");
}

template <class Evaluate>
void bm_evaluator(benchmark::State& state, const Case& c, Evaluate evaluate) {
  const auto rows = static_cast<std::size_t>(state.range(0));
  const Inputs in(c, rows);
  const auto tree = build_tree(in.e);
  if (!evaluators_agree(in, *tree, rows)) {
    state.SkipWithError("evaluate_batch and the recursive tree disagree");
    return;
  }
  std::vector<double> out(rows);
  for (auto _ : state) {
    evaluate(in, *tree, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_node_rows(state, in.e, rows);
}

void bm_batch(benchmark::State& state, const Case& c) {
  bm_evaluator(state, c, [](const Inputs& in, const TreeNode&, std::span<double> out) {
    expr::evaluate_batch(in.e, in.columns, out);
  });
}

void bm_batch_scalar_target(benchmark::State& state, const Case& c) {
  const simd::ScopedTarget scalar(simd::runnable_targets().back());
  bm_batch(state, c);
}

void bm_recursive(benchmark::State& state, const Case& c) {
  bm_evaluator(state, c, [](const Inputs& in, const TreeNode& tree, std::span<double> out) {
    evaluate_recursive(tree, in.columns, out);
  });
}

using CaseBenchmark = void (*)(benchmark::State&, const Case&);

void register_rows(const std::string& name, CaseBenchmark function, const Case& c, int rows) {
  benchmark::RegisterBenchmark((name + "/" + c.label).c_str(), function, c)
      ->ArgName("rows")
      ->Arg(rows);
}

[[maybe_unused]] const bool registered = [] {
  for (const Case& c : kCases) {
    for (const int rows : {50, 1000, 100000}) {
      register_rows("BM_ExprBatch", bm_batch, c, rows);
      register_rows("BM_ExprBatchScalarTarget", bm_batch_scalar_target, c, rows);
      register_rows("BM_ExprRecursive", bm_recursive, c, rows);
    }
  }
  return true;
}();

}  // namespace
