#include "expanded.h"

#include <algorithm>
#include <cmath>

namespace specula::fit {
namespace {

using expr::Node;
using expr::Op;

bool is_natural_exponent(const Node& n) {
  return n.op == Op::constant && n.value >= 0 && n.value == std::round(n.value) && n.value <= 64;
}

/// Every exponent vector of total degree ≤ `degree` over `variables` variables, lowest first.
void monomials(int degree, std::uint32_t variables, std::vector<int>& exponents,
               std::vector<std::vector<int>>& out) {
  if (exponents.size() == variables) {
    out.push_back(exponents);
    return;
  }
  int used = 0;
  for (int e : exponents) used += e;
  for (int e = 0; e + used <= degree; ++e) {
    exponents.push_back(e);
    monomials(degree, variables, exponents, out);
    exponents.pop_back();
  }
}

}  // namespace

std::optional<int> polynomial_degree(const Genome& g) {
  std::vector<std::optional<int>> degree;  // a stack, as the postfix array evaluates
  std::vector<bool> constant_only;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const Node& n = g[i];
    const int arity = expr::arity(n.op);
    std::optional<int> d;
    bool constant = false;
    if (arity == 0) {
      d = n.op == Op::variable ? 1 : 0;
      constant = n.op == Op::constant;
    } else if (arity == 1) {
      d = n.op == Op::neg ? degree.back() : std::nullopt;
      constant = constant_only.back();
    } else {
      const std::optional<int> a = degree[degree.size() - 2], b = degree.back();
      const bool b_constant = constant_only.back();
      constant = constant_only[constant_only.size() - 2] && b_constant;
      if (a && b) {
        if (n.op == Op::add || n.op == Op::sub) d = std::max(*a, *b);
        else if (n.op == Op::mul) d = *a + *b;
        else if (n.op == Op::div && b_constant) d = *a;
        else if (n.op == Op::pow && is_natural_exponent(g[i - 1])) d = *a * static_cast<int>(g[i - 1].value);
      }
      degree.pop_back(), constant_only.pop_back();
    }
    if (arity > 0) degree.pop_back(), constant_only.pop_back();
    if (!d && !constant) return std::nullopt;
    degree.push_back(constant ? std::optional<int>(0) : d);
    constant_only.push_back(constant);
  }
  return degree.size() == 1 ? degree.back() : std::nullopt;
}

std::size_t monomial_count(int degree, std::uint32_t variables) {
  double count = 1;  // C(degree + variables, variables)
  for (std::uint32_t k = 1; k <= variables; ++k) count = count * (degree + k) / k;
  return static_cast<std::size_t>(std::llround(count));
}

std::vector<std::vector<int>> monomial_exponents(int degree, std::uint32_t variables) {
  std::vector<std::vector<int>> out;
  std::vector<int> exponents;
  monomials(degree, variables, exponents, out);
  return out;
}

void append_monomial(Genome& out, const std::vector<int>& exponents, bool onto) {
  for (std::uint32_t v = 0; v < exponents.size(); ++v) {
    if (exponents[v] == 0) continue;
    out.push_back(Node{Op::variable, v, 0});
    if (exponents[v] > 1) {
      out.push_back(expr::exact_constant(exponents[v], 1, expr::Symbol::one));
      out.push_back(Node{Op::pow, 0, 0});
    }
    if (onto) out.push_back(Node{Op::mul, 0, 0});
    onto = true;
  }
}

Genome dense_polynomial(int degree, std::uint32_t variables) {
  const auto terms = monomial_exponents(degree, variables);
  Genome out;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    out.push_back(Node{Op::constant, 0, 1.0});
    append_monomial(out, terms[t], true);
    if (t > 0) out.push_back(Node{Op::add, 0, 0});
  }
  return out;
}

}  // namespace specula::fit
