// Tests of io/decimal_number.h, the token-to-number conversion of the CSV reader: the fast
// decimal path and the std::from_chars fallback must give strtod's value bit for bit, and the
// token rules (a leading '+', one pair of quotes, nan/inf, out-of-range values) hold.
#include "io/decimal_number.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <string_view>

namespace imunoise::io {
namespace {

using csv_detail::parse_decimal_prefix;
using csv_detail::parse_double;
using csv_detail::parse_int64;

std::optional<double> as_double(std::string_view token) {
  double v = 0.0;
  if (!parse_double(token.data(), token.data() + token.size(), v)) return std::nullopt;
  return v;
}

std::optional<std::int64_t> as_int64(std::string_view token) {
  std::int64_t v = 0;
  if (!parse_int64(token.data(), token.data() + token.size(), v)) return std::nullopt;
  return v;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(DecimalNumber, EveryPathGivesStrtodsValueBitForBit) {
  // Shortest round-trip text (up to 17 significant digits: the extended-precision path), 19-
  // and 20-digit forms (beyond 2^53, or beyond 19 digits: from_chars), leading zeros, exponents.
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  char buffer[64];
  int fast_taken = 0;
  for (int i = 0; i < 100000; ++i) {
    const double x = mantissa(rng) * std::pow(10.0, exponent(rng));
    switch (i % 5) {
      case 0:
        *std::to_chars(buffer, buffer + sizeof buffer, x).ptr = '\0';
        break;
      case 1:
        std::snprintf(buffer, sizeof buffer, "%.19g", x);
        break;
      case 2:
        std::snprintf(buffer, sizeof buffer, "%.20f", x / 1e6);
        break;
      case 3:
        std::snprintf(buffer, sizeof buffer, "%.16e", x);
        break;
      default:
        std::snprintf(buffer, sizeof buffer, "%.6f", x);
        break;
    }
    const std::string_view token(buffer);
    const double expected = std::strtod(buffer, nullptr);
    const std::optional<double> parsed = as_double(token);
    ASSERT_TRUE(parsed.has_value()) << token;
    ASSERT_TRUE(same_bits(*parsed, expected)) << token << " read as " << *parsed;
    // The fast path alone: where it takes a whole token, its value is strtod's too.
    const char* p = token.data();
    double fast = 0.0;
    if (parse_decimal_prefix(p, token.data() + token.size(), fast) &&
        p == token.data() + token.size()) {
      ++fast_taken;
      ASSERT_TRUE(same_bits(fast, expected)) << token << " fast path gave " << fast;
    }
  }
  EXPECT_GT(fast_taken, 50000) << "most tokens take the fast path";
}

TEST(DecimalNumber, PrefixStopsWhereTheNumberEnds) {
  const std::string_view text = "-1.25,3";
  const char* p = text.data();
  double v = 0.0;
  ASSERT_TRUE(parse_decimal_prefix(p, text.data() + text.size(), v));
  EXPECT_EQ(v, -1.25);
  EXPECT_EQ(p, text.data() + 5);  // at the ','
}

TEST(DecimalNumber, TokenRules) {
  EXPECT_EQ(as_double("+1.5"), 1.5);
  EXPECT_EQ(as_double("\"2\""), 2.0);
  EXPECT_EQ(as_double("\"+0.5e1\""), 5.0);
  EXPECT_TRUE(std::isnan(*as_double("nan")));
  EXPECT_EQ(as_double("-inf"), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(as_double("1e999"), std::numeric_limits<double>::infinity());  // like strtod
  EXPECT_EQ(as_double("1e-999"), 0.0);
  EXPECT_FALSE(as_double("+-1"));
  EXPECT_FALSE(as_double("++1"));
  EXPECT_FALSE(as_double(""));
  EXPECT_FALSE(as_double("1.5x"));
  EXPECT_FALSE(as_double("1,5"));
  EXPECT_FALSE(as_double("1e"));
  EXPECT_TRUE(csv_detail::is_number("0.25"));
  EXPECT_FALSE(csv_detail::is_number("gyro_x"));
}

TEST(DecimalNumber, Int64TokensAreExact) {
  EXPECT_EQ(as_int64("1403636579758555393"), 1403636579758555393);  // beyond 2^53
  EXPECT_EQ(as_int64("+5"), 5);
  EXPECT_EQ(as_int64("\"7\""), 7);
  EXPECT_EQ(as_int64("-9223372036854775808"), std::numeric_limits<std::int64_t>::min());
  EXPECT_FALSE(as_int64("9223372036854775808"));
  EXPECT_FALSE(as_int64("1.0"));
  EXPECT_FALSE(as_int64(""));
}

}  // namespace
}  // namespace imunoise::io
