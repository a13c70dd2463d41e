#pragma once
// A polynomial found in factored form, multiplied out (docs/fit.md, "Expanded polynomials"): the
// search's formula 4·x·(x + 0.60583)·((x + 0.0720852)² + 0.407461) is 4x⁴ + 3x³ + 2x² + x with its
// roots written out; the coefficients of the expanded form snap where the roots cannot.
#include <cstdint>
#include <optional>
#include <vector>

#include "genome.h"

namespace specula::fit {

/// The degree of `g` as a polynomial in its variables — built from constants, variables, +, −, ×,
/// negation, powers to constants that are integers in [0, 64] and divisions by constants — or nothing.
std::optional<int> polynomial_degree(const Genome& g);

/// How many monomials of total degree ≤ `degree` there are in `variables` variables.
std::size_t monomial_count(int degree, std::uint32_t variables);

/// Every exponent vector (eᵥ per variable) of total degree ≤ `degree`, lowest first.
std::vector<std::vector<int>> monomial_exponents(int degree, std::uint32_t variables);

/// Appends the factors xᵥ^eᵥ of one monomial (powers above 1 as exact-exponent ^), each
/// multiplied onto what precedes it when `onto` (a coefficient already written); otherwise the
/// first stands alone. Appends nothing for the constant monomial.
void append_monomial(Genome& out, const std::vector<int>& exponents, bool onto);

/// Σ c·Πxᵥ^eᵥ over every monomial of total degree ≤ `degree` (constants free, at 1; powers
/// above 1 as exact-exponent ^).
Genome dense_polynomial(int degree, std::uint32_t variables);

}  // namespace specula::fit
