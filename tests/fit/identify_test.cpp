// Elementary constants recognised by an integer relation (src/fit/identify.h).
#include "fit/identify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace specula::fit {
namespace {

using std::numbers::pi;

std::string text_of(const Genome& g) { return expr::to_infix(expr::Expression(g, {})); }

double value_of(const Genome& g) { return expr::evaluate(expr::Expression(g, {}), {}); }

TEST(IntegerRelation, FindsTheRelationOfALogOfAProductOfPowers) {
  // 2·ln(1/√(2π)) + ln 2 + ln π = 0.
  const std::vector<double> x = {std::log(1 / std::sqrt(2 * pi)), std::numbers::ln2, std::log(pi)};
  const auto relation = integer_relation(x, 6, 1e-12);
  ASSERT_TRUE(relation);
  const long long sign = (*relation)[0] > 0 ? 1 : -1;
  EXPECT_EQ(*relation, (std::vector<long long>{2 * sign, sign, sign}));
}

TEST(IntegerRelation, FindsNoneWhereNoneIsSmall) {
  // π, e and ln 2 have no known small relation; 1 + 1e-6 moves a relation past the tolerance.
  EXPECT_FALSE(integer_relation(std::vector<double>{pi, std::numbers::e, std::numbers::ln2}, 6, 1e-9));
  EXPECT_FALSE(integer_relation(std::vector<double>{2 * std::numbers::ln2 + 1e-6, std::numbers::ln2}, 6, 1e-9));
  EXPECT_TRUE(integer_relation(std::vector<double>{2 * std::numbers::ln2, std::numbers::ln2}, 6, 1e-9));  // control
  EXPECT_FALSE(integer_relation(std::vector<double>{1.0, 0.0}, 6, 1e-9));  // a zero entry: nothing
}

struct Known {
  double value;
  const char* text;
};

// The constants: each found from its double (and from one carrying a fitted constant's
// error, 1e-11 relative), printed as its closed form and equal to it to rounding.
const Known kKnown[] = {
    {std::exp(-0.5), "exp(-1 / 2)"},
    {1 / std::sqrt(2 * pi), "1 / sqrt(2 * pi)"},
    {std::sqrt(1.5), "sqrt(3 / 2)"},
    {std::log(3.0), "log(3)"},
    {pi * pi, "pi ^ 2"},
    {std::exp(-1.0), "exp(-1)"},
    {-std::sqrt(1.5), "-sqrt(3 / 2)"},
    {std::exp(-0.5) / std::sqrt(2 * pi), "exp(-1 / 2) / sqrt(2 * pi)"},
    {std::log(1.5) / 2, "0.5 * log(3 / 2)"},
};

TEST(ElementaryConstants, RecogniseTheClosedForms) {
  for (const Known& k : kKnown) {
    for (double drift : {0.0, 1e-11}) {
      const auto forms = elementary_constants(k.value * (1 + drift));
      ASSERT_FALSE(forms.empty()) << k.text << " drift " << drift;
      EXPECT_EQ(text_of(forms.front()), k.text);
      EXPECT_NEAR(value_of(forms.front()), k.value, 4e-16 * std::abs(k.value)) << k.text;
    }
  }
}

TEST(ElementaryConstants, OfferNothingForNumbersWithoutAClosedForm) {
  // Numbers a fit gives for a rough formula, and the known constants moved by 1e-7 (control: above).
  for (double value : {0.7236189, 1.234567891, 31.0 / 7.0 + 1e-4, -2.0004})
    EXPECT_TRUE(elementary_constants(value).empty()) << value;
  for (const Known& k : kKnown) EXPECT_TRUE(elementary_constants(k.value * (1 + 1e-7)).empty()) << k.text;
  EXPECT_TRUE(elementary_constants(0.75).empty());  // a plain 3/4: snap_candidates' business
  // Near ±1 and near 0 the relations are trivial (|v| = 1, d·v = ln 1): nothing, and no empty form.
  for (double value : {1 + 1e-10, -1 - 1e-10, 1e-11, -1e-12}) EXPECT_TRUE(elementary_constants(value).empty()) << value;
}

}  // namespace
}  // namespace specula::fit
