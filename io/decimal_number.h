/// @file
/// @brief Internal to the CSV reader (io/csv_reader.h): the conversion of one text token to a
/// number. A fast path reads the usual decimal tokens (at most 19 significant digits, small
/// exponents) with one correctly rounded operation; everything else goes through
/// std::from_chars (strtod for values beyond the double range). Inline: the row parser calls
/// these once per field.
#pragma once

#include <bit>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

namespace imunoise::io::csv_detail {

/// Removes one pair of surrounding double quotes (some tools quote every field).
inline void unquote(const char*& b, const char*& e) {
  if (e - b >= 2 && *b == '"' && e[-1] == '"') {
    ++b;
    --e;
  }
}

inline bool is_digit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

/// True when the 8 bytes (little-endian load) are all ASCII digits: every high nibble is 3,
/// and adding 6 to every low nibble does not carry into the high nibble (low nibble ≤ 9).
inline bool eight_digits(std::uint64_t chunk) {
  constexpr std::uint64_t kHigh = 0xF0F0F0F0F0F0F0F0u;
  constexpr std::uint64_t kThrees = 0x3030303030303030u;
  return (chunk & kHigh) == kThrees && ((chunk + 0x0606060606060606u) & kHigh) == kThrees;
}

/// Value of 8 ASCII digits loaded little-endian (first digit in the lowest byte): merge
/// neighbours into 2-, then 4-, then 8-digit lanes; no lane can carry into the next.
inline std::uint64_t eight_digit_value(std::uint64_t chunk) {
  std::uint64_t v = chunk - 0x3030303030303030u;
  v = (v * 10 + (v >> 8)) & 0x00FF00FF00FF00FFu;
  v = (v * 100 + (v >> 16)) & 0x0000FFFF0000FFFFu;
  return (v * 10000 + (v >> 32)) & 0xFFFFFFFFu;
}

/// Accumulates a run of digits into w (wrapping past 19 digits; callers check the count).
inline const char* scan_digits(const char* p, const char* e, std::uint64_t& w) {
  while (e - p >= 8) {
    std::uint64_t chunk;
    std::memcpy(&chunk, p, 8);
    if constexpr (std::endian::native != std::endian::little) break;
    if (!eight_digits(chunk)) break;
    w = w * 100000000u + eight_digit_value(chunk);
    p += 8;
  }
  for (; p != e && is_digit(*p); ++p) w = w * 10 + static_cast<std::uint64_t>(*p - '0');
  return p;
}

/// w × 10^q (or w / 10^−q) in x87 extended precision, rounded to double, for w < 2^64 and
/// |q| ≤ 27: w and 10^|q| (5^27 < 2^64) are exact 64-bit-significand operands, so the one
/// extended operation gives r = the correctly rounded 64-bit value of w·10^q. Rounding r to
/// double gives the correctly rounded double unless r is itself a midpoint between two doubles
/// (low 11 of its 64 significand bits = 100 0000 0000): a midpoint m strictly between the
/// exact value and r would be a 64-bit number nearer than r. Returns false in that case (about
/// 1 in 2048), and where long double is not the x87 format.
inline bool scale_extended(std::uint64_t w, int exp10, double& out) {
  if constexpr (std::numeric_limits<long double>::digits != 64 ||
                std::endian::native != std::endian::little) {
    return false;
  } else {
    static constexpr long double kPow10[] = {1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,
                                             1e7L,  1e8L,  1e9L,  1e10L, 1e11L, 1e12L, 1e13L,
                                             1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L, 1e20L,
                                             1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};
    if (exp10 < -27 || exp10 > 27) return false;
    const auto v = static_cast<long double>(w);
    const long double r = exp10 < 0 ? v / kPow10[-exp10] : v * kPow10[exp10];
    std::uint64_t significand = 0;  // x87 layout: the explicit 64-bit significand comes first
    std::memcpy(&significand, &r, sizeof significand);
    if ((significand & 0x7FF) == 0x400) return false;
    out = static_cast<double>(r);
    return true;
  }
}

/// Fast path for the usual decimal tokens, value w·10^q with at most 19 significant digits.
/// With w ≤ 2^53 and |q| ≤ 22, w × 10^q or w / 10^−q has exact operands, so one correctly
/// rounded operation gives the correctly rounded result (Clinger, "How to Read Floating Point
/// Numbers Accurately", PLDI 1990, §5); the 17-digit shortest round-trip text of most doubles
/// goes through scale_extended. Scans the number starting at P and leaves P after it;
/// returns false for anything else (more digits, large exponents, nan/inf, garbage), and the
/// caller then uses std::from_chars. What follows the number is the caller's to check: the
/// result depends only on the bytes before P, so it is the same as for the token ending at P.
inline bool parse_decimal_prefix(const char*& p, const char* e, double& out) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const bool negative = p != e && *p == '-';
  if (negative) ++p;
  const char* const digits_begin = p;
  std::uint64_t w = 0;
  p = scan_digits(p, e, w);
  std::ptrdiff_t digits = p - digits_begin;
  int exp10 = 0;
  if (p != e && *p == '.') {
    const char* frac_begin = ++p;
    p = scan_digits(p, e, w);
    digits += p - frac_begin;
    exp10 = -static_cast<int>(p - frac_begin);
  }
  if (digits == 0) return false;
  if (digits > 19) {
    // Leading zeros ("0.000123…") add digits but not to w: count only the significant ones.
    std::ptrdiff_t zeros = 0;
    for (const char* z = digits_begin; z != p && (*z == '0' || *z == '.'); ++z) zeros += *z == '0';
    if (digits - zeros > 19) return false;  // w has wrapped
  }
  if (p != e && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool exp_negative = p != e && *p == '-';
    if (p != e && (*p == '-' || *p == '+')) ++p;
    if (p == e || !is_digit(*p)) return false;
    int x = 0;
    for (; p != e && is_digit(*p); ++p) {
      if (x < 100000) x = x * 10 + (*p - '0');  // beyond ±27 we fall back anyway
    }
    exp10 += exp_negative ? -x : x;
  }
  double v = 0.0;
  if (w == 0) {
    v = 0.0;
  } else if (w <= (std::uint64_t{1} << 53) && exp10 >= -22 && exp10 <= 22) {
    v = static_cast<double>(w);
    v = exp10 < 0 ? v / kPow10[-exp10] : v * kPow10[exp10];
  } else if (!scale_extended(w, exp10, v)) {
    return false;
  }
  out = negative ? -v : v;
  return true;
}

/// parse_decimal_prefix over a whole token [p, e).
inline bool parse_decimal_fast(const char* p, const char* e, double& out) {
  return parse_decimal_prefix(p, e, out) && p == e;
}

/// Parses a whole token as a double. Accepts a leading '+', nan/inf spellings (reported as
/// non-finite by the caller) and values beyond double range (→ ±inf or 0 like strtod).
/// Kept out of line: it is the general path (quoted, '+', relative or odd tokens), and inlined
/// into the field conversion of io/csv_row_parser.cpp it makes that too large for GCC to
/// inline into parse_row, which then calls it for every field, requested or not (+15%
/// instructions reading one column of seven, by callgrind; the reader before the split had it
/// out of line too).
[[gnu::noinline]] inline bool parse_double(const char* b, const char* e, double& out) {
  unquote(b, e);
  if (b != e && *b == '+') {  // from_chars rejects '+', but "+1.5" is a fine number
    ++b;
    if (b != e && (*b == '-' || *b == '+')) return false;
  }
  if (parse_decimal_fast(b, e, out)) return true;
  const auto [p, ec] = std::from_chars(b, e, out);
  if (p != e || b == e) return false;
  if (ec == std::errc()) return true;
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(b, e);  // rare path: let strtod pick ±HUGE_VAL or a denormal/0
    out = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return false;
}

/// Whole token as a 64-bit integer (exact time stamps in ns do not fit a double's 53 bits).
inline bool parse_int64(const char* b, const char* e, std::int64_t& out) {
  unquote(b, e);
  if (b != e && *b == '+') ++b;
  const auto [p, ec] = std::from_chars(b, e, out);
  return ec == std::errc() && p == e && b != e;
}

/// True when the whole token parses as a double (as parse_double accepts it).
inline bool is_number(std::string_view token) {
  double v = 0.0;
  return parse_double(token.data(), token.data() + token.size(), v);
}

}  // namespace imunoise::io::csv_detail
