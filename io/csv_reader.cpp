#include "io/csv_reader.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "common/errors.h"
#include "common/huge_pages.h"
#include "common/parallel_for.h"
#include "io/mapping_guard.h"

namespace imunoise::io {

namespace {

constexpr std::size_t kBlockBytes = std::size_t{1} << 20;     // one read() call
constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;  // beyond: not a numeric table
constexpr std::size_t kSniffBytes = std::size_t{256} << 10;   // enough for the first lines
constexpr std::size_t kMaxSniffBytes = std::size_t{8} << 20;  // long comment preambles
constexpr std::size_t kSniffLines = 64;
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

std::string errno_text(int err) { return std::generic_category().message(err); }

/// Printable, bounded rendering of file text for messages: binary garbage stays one line.
std::string show(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  if (text.size() > kMax) out += "...";
  return out;
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// The field of a SEP-delimited line that starts at P: [B, E) with blanks trimmed. Returns the
/// separator that ends it, or nullptr when it runs to END.
inline const char* delimited_field(const char* p, const char* end, char sep, const char*& b,
                                   const char*& e) {
  const char* d = static_cast<const char*>(std::memchr(p, sep, static_cast<std::size_t>(end - p)));
  const char* fe = d != nullptr ? d : end;
  b = p;
  while (b != fe && is_blank(*b)) ++b;
  e = fe;
  while (e != b && is_blank(e[-1])) --e;
  return d;
}

/// Reads a file in large blocks and hands out lines as views into its buffer (valid until the
/// next call). Strips "\n", "\r\n" and a UTF-8 BOM on line 1; a last line without a newline is
/// still a line. Lines longer than kMaxLineBytes are an error, so memory stays bounded.
class LineSource {
 public:
  explicit LineSource(const std::string& path) : path_(path) {
    do {
      fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    } while (fd_ < 0 && errno == EINTR);
    if (fd_ < 0) {
      const int err = errno;
      std::string what = "cannot open: ";
      what.append(errno_text(err));
      if (err == ENOENT)
        what.append(" (check the path; relative paths start at the current directory)");
      throw InputError(located_message(path, 0, 0, what));
    }
    struct stat st {};
    if (::fstat(fd_, &st) == 0) {
      if (S_ISDIR(st.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        throw InputError(located_message(path, 0, 0, "is a directory, not a data file"));
      }
      if (S_ISREG(st.st_mode)) size_hint_ = static_cast<std::size_t>(st.st_size);
    }
    buffer_.resize(kBlockBytes);
  }
  ~LineSource() {
    if (fd_ >= 0) ::close(fd_);
  }
  LineSource(const LineSource&) = delete;
  LineSource& operator=(const LineSource&) = delete;

  std::size_t size_hint() const { return size_hint_; }
  int fd() const { return fd_; }
  bool at_eof() const { return eof_; }
  /// Reports the bytes read after each block from now on (regular files only: the size is
  /// the total).
  void set_progress(const ProgressCallback* progress) { progress_ = progress; }

  /// The unconsumed bytes, after reading until at least `bytes` are buffered or EOF.
  std::string_view peek(std::size_t bytes) {
    while (end_ - pos_ < bytes && !eof_) read_more();
    return {buffer_.data() + pos_, end_ - pos_};
  }

  /// Next line, or false at end of file.
  bool next(std::string_view& line) {
    for (;;) {
      const char* base = buffer_.data();
      const void* nl = std::memchr(base + scan_, '\n', end_ - scan_);
      if (nl != nullptr) {
        const auto at = static_cast<std::size_t>(static_cast<const char*>(nl) - base);
        line = {base + pos_, at - pos_};
        pos_ = scan_ = at + 1;
        break;
      }
      scan_ = end_;  // no newline in what we have: do not scan it again
      if (eof_) {
        if (pos_ == end_) return false;
        line = {base + pos_, end_ - pos_};
        pos_ = scan_ = end_;
        break;
      }
      read_more();
    }
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_number_ == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
      line.remove_prefix(kUtf8Bom.size());
    }
    return true;
  }

  std::int64_t line_number() const { return line_number_; }

 private:
  void read_more() {
    if (pos_ > 0) {  // keep only the unconsumed tail (a partial line)
      std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
      end_ -= pos_;
      scan_ -= pos_;
      pos_ = 0;
    }
    if (end_ == buffer_.size()) {
      if (buffer_.size() >= kMaxLineBytes) {
        throw InputError(located_message(path_, line_number_ + 1, 0,
                                         "line longer than 16 MiB: not a numeric text table"));
      }
      buffer_.resize(buffer_.size() * 2);
    }
    ssize_t got = 0;
    do {
      got = ::read(fd_, buffer_.data() + end_, buffer_.size() - end_);
    } while (got < 0 && errno == EINTR);
    if (got < 0) {
      throw InputError(
          located_message(path_, line_number_ + 1, 0, "cannot read: " + errno_text(errno)));
    }
    if (got == 0) {
      eof_ = true;
    } else {
      end_ += static_cast<std::size_t>(got);
      bytes_read_ += static_cast<std::size_t>(got);
      if (progress_ != nullptr && size_hint_ > 0) {
        report_progress(*progress_, "reading",
                        static_cast<std::int64_t>(std::min(bytes_read_, size_hint_)),
                        static_cast<std::int64_t>(size_hint_));
      }
    }
  }

  std::string path_;
  int fd_ = -1;
  std::size_t size_hint_ = 0;
  std::vector<char> buffer_;
  std::size_t pos_ = 0;   // start of the unconsumed bytes
  std::size_t scan_ = 0;  // where the next newline search starts
  std::size_t end_ = 0;   // end of the valid bytes
  bool eof_ = false;
  std::int64_t line_number_ = 0;
  std::size_t bytes_read_ = 0;
  const ProgressCallback* progress_ = nullptr;  // not owned; set only during TableReader::read
};

bool is_content(std::string_view line) {
  for (char c : line) {
    if (!is_blank(c)) return c != '#';
  }
  return false;
}

char delimiter_char(Delimiter d) {
  switch (d) {
    case Delimiter::kComma:
      return ',';
    case Delimiter::kTab:
      return '\t';
    case Delimiter::kSemicolon:
      return ';';
    default:
      return ' ';
  }
}

/// Calls on_field(index, begin, end) for each field of `line` (trimmed of blanks) and returns
/// the field count. Whitespace mode: runs of blanks separate, leading/trailing ones are ignored.
template <typename OnField>
inline std::size_t for_each_field(std::string_view line, Delimiter delimiter, OnField&& on_field) {
  const char* p = line.data();
  const char* const end = p + line.size();
  std::size_t index = 0;
  if (delimiter == Delimiter::kWhitespace) {
    for (;;) {
      while (p != end && is_blank(*p)) ++p;
      if (p == end) return index;
      const char* b = p;
      while (p != end && !is_blank(*p)) ++p;
      on_field(index++, b, p);
    }
  }
  const char sep = delimiter_char(delimiter);
  for (;;) {
    const char* b;
    const char* e;
    const char* d = delimited_field(p, end, sep, b, e);
    on_field(index++, b, e);
    if (d == nullptr) return index;
    p = d + 1;
  }
}

std::vector<std::string_view> split_fields(std::string_view line, Delimiter delimiter) {
  std::vector<std::string_view> out;
  for_each_field(line, delimiter, [&](std::size_t, const char* b, const char* e) {
    out.emplace_back(b, static_cast<std::size_t>(e - b));
  });
  return out;
}

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
inline bool parse_double(const char* b, const char* e, double& out) {
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

bool is_number(std::string_view token) {
  double v = 0.0;
  return parse_double(token.data(), token.data() + token.size(), v);
}

Delimiter detect_delimiter(const std::vector<std::string_view>& lines) {
  // Prefer a separator present with the same count on every line, then one merely present
  // on every line (the row-count check reports the odd line); else blanks separate.
  for (const bool need_same_count : {true, false}) {
    for (const Delimiter d : {Delimiter::kTab, Delimiter::kSemicolon, Delimiter::kComma}) {
      const char c = delimiter_char(d);
      bool ok = !lines.empty();
      std::ptrdiff_t first_count = -1;
      for (std::string_view line : lines) {
        const auto count = std::count(line.begin(), line.end(), c);
        if (count == 0 || (need_same_count && first_count >= 0 && count != first_count)) {
          ok = false;
          break;
        }
        first_count = count;
      }
      if (ok) return d;
    }
  }
  return Delimiter::kWhitespace;
}

std::string header_name(std::string_view field) {
  const char* b = field.data();
  const char* e = b + field.size();
  unquote(b, e);
  return std::string(b, e);
}

}  // namespace

// ---------------------------------------------------------------------------------------------

std::string TableLayout::column_label(std::size_t index) const {
  const std::string number = "column " + std::to_string(index + 1);
  if (index < column_names.size() && !column_names[index].empty()) {
    return "'" + show(column_names[index]) + "' (" + number + ")";
  }
  return number;
}

std::string TableLayout::describe_columns() const {
  if (!has_header()) {
    return column_count == 1
               ? std::string("1 (no header row)")
               : "1.." + std::to_string(column_count) + " (no header row; use 1-based indices)";
  }
  constexpr std::size_t kMaxListed = 40;  // keep error messages one readable line
  std::string out;
  for (std::size_t i = 0; i < column_names.size(); ++i) {
    if (i == kMaxListed) {
      out += ", ... (" + std::to_string(column_names.size() - kMaxListed) + " more)";
      break;
    }
    if (i > 0) out += ", ";
    out +=
        column_names[i].empty() ? "(unnamed " + std::to_string(i + 1) + ")" : show(column_names[i]);
  }
  return out;
}

void LineMap::add(std::int64_t row, std::int64_t line) {
  if (breaks_.empty() || row != next_row_ || line != next_line_) breaks_.emplace_back(row, line);
  next_row_ = row + 1;
  next_line_ = line + 1;
}

void LineMap::add_run(std::int64_t row, std::int64_t line, std::int64_t count) {
  if (count <= 0) return;
  add(row, line);  // the rest of the run continues it: add() would record nothing for them
  next_row_ = row + count;
  next_line_ = line + count;
}

std::int64_t LineMap::line_of(std::size_t row) const {
  const auto r = static_cast<std::int64_t>(row);
  auto it = std::upper_bound(breaks_.begin(), breaks_.end(), r,
                             [](std::int64_t value, const auto& b) { return value < b.first; });
  if (it == breaks_.begin()) return 0;
  --it;
  return it->second + (r - it->first);
}

// ---------------------------------------------------------------------------------------------
// Row conversion, shared by the streamed and the memory-mapped paths so both give the same
// values and the same errors.

namespace {

/// What one read() extracts, shared read-only by all workers.
struct ReadPlan {
  std::size_t column_count = 0;
  Delimiter delimiter = Delimiter::kWhitespace;
  char separator = ' ';
  bool drop_non_finite = false;
  std::vector<int> slot_of;             // per file column: output slot, or -1 when not read
  std::vector<unsigned char> relative;  // per slot; not vector<bool>: read per field
  std::size_t slot_count() const { return relative.size(); }
};

enum class RowProblem {
  kNone,
  kEmptyField,
  kMalformedNumber,
  kNonFinite,
  kColumnCount,
  kLineTooLong,
};

/// A refused line, kept as data: workers then neither allocate nor throw, and the message is
/// written once the line's number in the file is known.
struct RowError {
  RowProblem problem = RowProblem::kNone;
  std::int64_t line = 0;         // 1-based; within its chunk until resolved
  std::int64_t column = 0;       // 1-based byte in the line; 0 = the whole line
  std::size_t field = 0;         // 0-based file column of a field problem
  std::size_t fields_found = 0;  // kColumnCount
  std::string_view token;        // the offending field (a view into the text)
};

std::string describe(const RowError& error, const TableLayout& layout,
                     const std::string& count_origin) {
  switch (error.problem) {
    case RowProblem::kEmptyField:
      return "empty field in " + layout.column_label(error.field);
    case RowProblem::kMalformedNumber:
      return "malformed number '" + show(error.token) + "' in " + layout.column_label(error.field);
    case RowProblem::kNonFinite:
      return "non-finite value '" + show(error.token) + "' in " + layout.column_label(error.field) +
             " (set drop_non_finite / --drop-non-finite to drop such rows)";
    case RowProblem::kColumnCount:
      return "expected " + std::to_string(layout.column_count) + " columns (" + count_origin +
             "), found " + std::to_string(error.fields_found);
    case RowProblem::kLineTooLong:
      return "line longer than 16 MiB: not a numeric text table";
    case RowProblem::kNone:
      break;
  }
  return "internal error: no row problem";
}

/// One row's values per slot; scratch sized once per thread.
struct RowValues {
  explicit RowValues(std::size_t slots) : value(slots), integer(slots), is_integer(slots) {}
  std::vector<double> value;
  std::vector<std::int64_t> integer;  // relative slots holding an integer token
  std::vector<unsigned char> is_integer;
  std::int64_t non_finite = 0;  // NaN/Inf values (only when dropping)
};

/// The first kept row's relative columns: what every kept row is made relative to.
struct Origin {
  explicit Origin(std::size_t slots) : value(slots, 0.0), integer(slots, 0), is_integer(slots, 0) {}
  std::vector<double> value;  // as written (first_values)
  std::vector<std::int64_t> integer;
  std::vector<unsigned char> is_integer;

  void set(const ReadPlan& plan, const RowValues& row) {
    for (std::size_t s = 0; s < plan.slot_count(); ++s) {
      if (!plan.relative[s]) continue;
      is_integer[s] = row.is_integer[s];
      integer[s] = row.integer[s];
      value[s] = row.is_integer[s] ? static_cast<double>(row.integer[s]) : row.value[s];
    }
  }

  /// Slot S of ROW relative to the origin: exact integer subtraction when both are integers
  /// (ns stamps beyond 2^53), else in double.
  double relative(std::size_t s, const RowValues& row) const {
    std::int64_t diff = 0;
    if (row.is_integer[s] && is_integer[s] &&
        !__builtin_sub_overflow(row.integer[s], integer[s], &diff)) {
      return static_cast<double>(diff);
    }
    const double v = row.is_integer[s] ? static_cast<double>(row.integer[s]) : row.value[s];
    return v - value[s];
  }
};

/// Converts field J = [b, e) (trimmed) of the line starting at LINE_BEGIN. False with ERROR
/// set when the field is refused.
inline bool convert_field(const ReadPlan& plan, std::size_t j, const char* line_begin,
                          const char* b, const char* e, RowValues& row, RowError& error) {
  const int slot = plan.slot_of[j];
  if (slot < 0) return true;  // not requested: counted, not converted
  const auto s = static_cast<std::size_t>(slot);
  const auto column = static_cast<std::int64_t>(b - line_begin) + 1;
  if (b == e) {
    error = {RowProblem::kEmptyField, 0, column, j, 0, {}};
    return false;
  }
  row.is_integer[s] = plan.relative[s] && parse_int64(b, e, row.integer[s]);
  if (row.is_integer[s]) return true;
  double v = 0.0;
  if (!parse_double(b, e, v)) {
    error = {RowProblem::kMalformedNumber, 0, column, j, 0, {b, static_cast<std::size_t>(e - b)}};
    return false;
  }
  if (!std::isfinite(v)) {
    if (!plan.drop_non_finite) {
      error = {RowProblem::kNonFinite, 0, column, j, 0, {b, static_cast<std::size_t>(e - b)}};
      return false;
    }
    ++row.non_finite;
  }
  row.value[s] = v;
  return true;
}

/// The fast path of a requested plain column: a decimal number that ends where the field
/// ends. Then the field is exactly the number's bytes (no blanks, quotes or '+'), and
/// parse_double on it would take the same parse_decimal_prefix path: same value. P moves past
/// the number.
inline bool convert_plain_number(const ReadPlan& plan, std::size_t j, const char*& p,
                                 const char* end, RowValues& row) {
  if (j >= plan.column_count) return false;
  const int slot = plan.slot_of[j];
  if (slot < 0 || plan.relative[static_cast<std::size_t>(slot)]) return false;
  const char* q = p;
  double v = 0.0;
  if (!parse_decimal_prefix(q, end, v)) return false;
  if (q != end) {
    const bool field_ends =
        plan.delimiter == Delimiter::kWhitespace ? is_blank(*q) : *q == plan.separator;
    if (!field_ends) return false;
  }
  row.value[static_cast<std::size_t>(slot)] = v;
  p = q;
  return true;
}

/// Splits a content line like for_each_field and converts the requested fields, in field
/// order, so the first refused field is the one reported. False with ERROR (line unset) when
/// the line is refused; ROW.non_finite > 0 means the row is to be dropped.
inline bool parse_row(const ReadPlan& plan, std::string_view line, RowValues& row,
                      RowError& error) {
  row.non_finite = 0;
  const char* const begin = line.data();
  const char* const end = begin + line.size();
  const std::size_t ncols = plan.column_count;
  const char* p = begin;
  std::size_t count = 0;
  const char* extra_field = nullptr;  // first field beyond the expected count
  if (plan.delimiter == Delimiter::kWhitespace) {
    for (;;) {
      while (p != end && is_blank(*p)) ++p;
      if (p == end) break;
      if (convert_plain_number(plan, count, p, end, row)) {
        ++count;
        continue;
      }
      const char* b = p;
      while (p != end && !is_blank(*p)) ++p;
      if (count < ncols) {
        if (!convert_field(plan, count, begin, b, p, row, error)) return false;
      } else if (count == ncols) {
        extra_field = b;
      }
      ++count;
    }
  } else {
    const char sep = plan.separator;
    for (;;) {
      if (convert_plain_number(plan, count, p, end, row)) {
        ++count;
        if (p == end) break;
        ++p;  // past the separator
        continue;
      }
      const char* b;
      const char* e;
      const char* d = delimited_field(p, end, sep, b, e);
      if (count < ncols) {
        if (!convert_field(plan, count, begin, b, e, row, error)) return false;
      } else if (count == ncols) {
        extra_field = b;
      }
      ++count;
      if (d == nullptr) break;
      p = d + 1;
    }
  }
  if (count != ncols) {
    const auto column = extra_field != nullptr ? static_cast<std::int64_t>(extra_field - begin) + 1
                                               : static_cast<std::int64_t>(line.size()) + 1;
    error = {RowProblem::kColumnCount, 0, column, 0, count, {}};
    return false;
  }
  return true;
}

/// Cuts the next line off [p, end): strips "\n" and "\r\n". The caller strips the BOM.
inline std::string_view cut_line(const char*& p, const char* end) {
  const auto* nl =
      static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
  const char* line_end = nl != nullptr ? nl : end;
  std::string_view line(p, static_cast<std::size_t>(line_end - p));
  p = nl != nullptr ? nl + 1 : end;
  return line;
}

/// LineSource's limit, applied to a mapped line (CR included, as LineSource counts it).
inline bool line_too_long(std::string_view line) { return line.size() >= kMaxLineBytes; }

inline void strip_cr(std::string_view& line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
}

/// A read-only private mapping of a whole regular file, unmapped on destruction. Guarded
/// (io/mapping_guard.h): if the file shrinks while it is parsed, the pages past its new end
/// read as zeros instead of killing the process, and truncated() says so.
class MappedText {
 public:
  MappedText() = default;
  ~MappedText() {
    guard_.reset();  // before the range can be reused by another mapping
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedText(const MappedText&) = delete;
  MappedText& operator=(const MappedText&) = delete;

  /// Maps FD; false (nothing mapped) when the file is not a regular file or mmap fails.
  bool map(int fd) {
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return false;
    const auto size = static_cast<std::size_t>(st.st_size);
    void* at = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    if (at == MAP_FAILED) return false;
    data_ = static_cast<const char*>(at);
    size_ = size;
    guard_.emplace(at, size);
    ::madvise(at, size, MADV_SEQUENTIAL);  // a hint: more read-ahead on a cold cache
    return true;
  }

  /// True when a page past the file's end was read: the file shrank after it was mapped.
  bool truncated() const { return guard_ && guard_->truncated(); }

  const char* begin() const { return data_; }
  const char* end() const { return data_ + size_; }
  std::size_t size() const { return size_; }

  /// Drops the mapping's pages wholly inside [b, e) from this process's memory (they stay in
  /// the page cache, and come back on the next access): the resident size then stays near the
  /// output's, not output + file.
  void release(const char* b, const char* e) const {
    const auto page = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    const auto base = reinterpret_cast<std::uintptr_t>(data_);
    const std::uintptr_t from = (reinterpret_cast<std::uintptr_t>(b) + page - 1) / page * page;
    const std::uintptr_t to = std::max(from, reinterpret_cast<std::uintptr_t>(e) / page * page);
    if (to > from && from >= base) {
      ::madvise(reinterpret_cast<void*>(from), to - from, MADV_DONTNEED);
    }
  }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
  std::optional<MappingGuard> guard_;
};

/// Consecutive kept rows on consecutive lines, chunk-local (LineMap::add_run after the join).
struct LineRun {
  std::int64_t row = 0;
  std::int64_t line = 0;
  std::int64_t count = 0;
};

/// A piece of the mapped data region, starting at a line start and ending after a newline (or
/// at the end of the file).
struct Chunk {
  const char* begin = nullptr;
  const char* end = nullptr;
  std::int64_t lines = 0;         // lines starting in the chunk (pass 1)
  std::int64_t lines_before = 0;  // file lines before the chunk
  std::size_t row_begin = 0;      // first output row it may fill
  std::size_t row_capacity = 0;   // rows it may fill: a bound on its kept rows
  std::size_t kept = 0;
  std::int64_t rows_dropped = 0;
  std::int64_t non_finite_dropped = 0;
  std::vector<LineRun> runs;
  RowError error;  // the chunk's first refused line (problem kNone: none)
};

/// Counts '\n' in [b, e), 8 bytes per step: a byte of x = word ^ "\n\n…" is zero exactly when
/// bit 7 of ((x & 0x7F…) + 0x7F…) | x is clear (no carry crosses a byte: each lane is ≤ 0xFE).
/// The multiply sums the 0/1 bytes into the top byte (at most 8: no carry out); a portable
/// popcount without -mpopcnt would be a library call.
std::int64_t count_newlines(const char* b, const char* e) {
  constexpr std::uint64_t kNewlines = 0x0A0A0A0A0A0A0A0Au;
  constexpr std::uint64_t kLow7 = 0x7F7F7F7F7F7F7F7Fu;
  std::int64_t n = 0;
  for (; e - b >= 8; b += 8) {
    std::uint64_t word;
    std::memcpy(&word, b, 8);
    const std::uint64_t x = word ^ kNewlines;
    const std::uint64_t found = ~(((x & kLow7) + kLow7) | x | kLow7) >> 7;  // 0 or 1 per byte
    n += static_cast<std::int64_t>((found * 0x0101010101010101u) >> 56);    // sum of the bytes
  }
  for (; b != e; ++b) n += *b == '\n';
  return n;
}

}  // namespace

namespace {

/// Sequential handling of lines in file order: the streamed path, and the mapped path up to
/// its first kept row. Throws at the first refused line.
class SequentialRows {
 public:
  SequentialRows(const ReadPlan& plan, const TableLayout& layout, std::int64_t header_line,
                 const std::string& count_origin, TableData& data, Origin& origin)
      : plan_(plan),
        layout_(layout),
        header_line_(header_line),
        count_origin_(count_origin),
        data_(data),
        origin_(origin),
        row_(plan.slot_count()) {}

  /// Takes line LINE_NO (CR and BOM stripped). True when it is kept, as row kept() − 1, with
  /// its final values (relative columns made relative) in values().
  bool take(std::string_view line, std::int64_t line_no) {
    if (!is_content(line) || line_no == header_line_) return false;
    RowError error;
    if (!parse_row(plan_, line, row_, error)) fail(error, line_no);
    if (row_.non_finite > 0) {
      ++data_.rows_dropped;
      data_.non_finite_dropped += row_.non_finite;
      return false;
    }
    if (kept_ == 0) {
      origin_.set(plan_, row_);
      data_.first_data_line = line_no;
    }
    for (std::size_t s = 0; s < plan_.slot_count(); ++s) {
      if (plan_.relative[s]) row_.value[s] = origin_.relative(s, row_);
    }
    data_.lines.add(kept_, line_no);
    ++kept_;
    return true;
  }

  const std::vector<double>& values() const { return row_.value; }
  std::int64_t kept() const { return kept_; }

  [[noreturn]] void fail(const RowError& error, std::int64_t line_no) const {
    throw InputError(located_message(layout_.path, line_no, error.column,
                                     describe(error, layout_, count_origin_)));
  }

 private:
  const ReadPlan& plan_;
  const TableLayout& layout_;
  std::int64_t header_line_;
  const std::string& count_origin_;
  TableData& data_;
  Origin& origin_;
  RowValues row_;
  std::int64_t kept_ = 0;
};

/// Parses CHUNK into its slice of the output columns (OUT[s] + chunk.row_begin …). Stops at
/// its first refused line, or early once a chunk before it (index < INDEX) has failed.
void parse_chunk(const ReadPlan& plan, const Origin& origin, Chunk& chunk, std::size_t index,
                 const std::vector<double*>& out, std::atomic<std::size_t>& first_failed) {
  constexpr std::int64_t kCheckEvery = 4096;  // lines between looks at first_failed
  RowValues row(plan.slot_count());
  const std::size_t slots = plan.slot_count();
  const char* p = chunk.begin;
  std::int64_t line_no = 0;  // within the chunk, 1-based
  std::size_t kept = 0;
  while (p != chunk.end) {
    std::string_view line = cut_line(p, chunk.end);
    ++line_no;
    if ((line_no % kCheckEvery) == 0 && first_failed.load(std::memory_order_relaxed) < index) {
      break;  // an earlier chunk's error wins; this chunk's rows no longer matter
    }
    if (line_too_long(line)) {
      chunk.error = {RowProblem::kLineTooLong, line_no, 0, 0, 0, {}};
      break;
    }
    strip_cr(line);  // line 1 (the only one with a BOM) is never in a chunk
    if (!is_content(line)) continue;
    if (!parse_row(plan, line, row, chunk.error)) {
      chunk.error.line = line_no;
      break;
    }
    if (row.non_finite > 0) {
      ++chunk.rows_dropped;
      chunk.non_finite_dropped += row.non_finite;
      continue;
    }
    assert(kept < chunk.row_capacity && "the bound on kept rows per chunk holds");
    const std::size_t at = chunk.row_begin + kept;
    for (std::size_t s = 0; s < slots; ++s) {
      out[s][at] = plan.relative[s] ? origin.relative(s, row) : row.value[s];
    }
    const auto row_index = static_cast<std::int64_t>(kept);
    if (chunk.runs.empty() || chunk.runs.back().row + chunk.runs.back().count != row_index ||
        chunk.runs.back().line + chunk.runs.back().count != line_no) {
      chunk.runs.push_back({row_index, line_no, 0});
    }
    ++chunk.runs.back().count;
    ++kept;
  }
  chunk.kept = kept;
  if (chunk.error.problem != RowProblem::kNone) {
    std::size_t seen = first_failed.load();
    while (index < seen && !first_failed.compare_exchange_weak(seen, index)) {
    }
  }
}

}  // namespace

struct TableReader::Impl {
  std::string path;
  LineSource source;
  TableLayout layout;
  std::int64_t first_data_line = 0;  // first content line that is not the header
  double mean_line_bytes = 0.0;
  bool consumed = false;

  explicit Impl(std::string p) : path(std::move(p)), source(path) {}

  [[noreturn]] void fail(std::int64_t line, std::int64_t column, const std::string& what) const {
    throw InputError(located_message(path, line, column, what));
  }

  void sniff(Delimiter requested) {
    layout.path = path;
    std::string_view head = source.peek(kSniffBytes);
    if (head.empty()) fail(0, 0, "file is empty");
    if (head.substr(0, 2) == "\xFF\xFE" || head.substr(0, 2) == "\xFE\xFF") {
      fail(1, 1, "text is UTF-16 encoded; save it as UTF-8 or ASCII");
    }
    if (const auto nul = head.find('\0'); nul != std::string_view::npos) {
      const std::string_view before = head.substr(0, nul);
      const auto line = 1 + std::count(before.begin(), before.end(), '\n');
      const auto line_start = before.rfind('\n');
      const auto column = line_start == std::string_view::npos ? nul + 1 : nul - line_start;
      fail(line, static_cast<std::int64_t>(column), "binary data (NUL byte): not a text table");
    }

    // The first content lines, with their line numbers (views into the peeked buffer).
    std::vector<std::string_view> lines;
    std::vector<std::int64_t> numbers;
    for (std::size_t want = kSniffBytes;; want *= 2) {
      head = source.peek(want);
      lines.clear();
      numbers.clear();
      std::int64_t number = 0;
      std::size_t pos = 0;
      std::size_t bytes = 0;
      while (pos < head.size() && lines.size() < kSniffLines) {
        const auto nl = head.find('\n', pos);
        if (nl == std::string_view::npos && !source.at_eof()) break;  // incomplete line
        const auto stop = nl == std::string_view::npos ? head.size() : nl;
        std::string_view line = head.substr(pos, stop - pos);
        bytes += line.size() + 1;
        pos = stop + 1;
        ++number;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (number == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
          line.remove_prefix(kUtf8Bom.size());
        }
        if (is_content(line)) {
          lines.push_back(line);
          numbers.push_back(number);
        }
      }
      mean_line_bytes = number > 0 ? static_cast<double>(bytes) / static_cast<double>(number) : 0;
      if (lines.size() >= 2 || source.at_eof() || want >= kMaxSniffBytes) break;
    }
    if (lines.empty()) {
      if (source.at_eof()) fail(0, 0, "no data rows (only comments and blank lines)");
      fail(0, 0, "no data row in the first 8 MiB: not a numeric text table");
    }

    layout.delimiter = requested != Delimiter::kAuto ? requested : detect_delimiter(lines);
    const std::vector<std::string_view> first = split_fields(lines[0], layout.delimiter);
    // A header row holds no number at all; a row mixing words and numbers is a data row with
    // a malformed token, which the read loop then reports precisely.
    const bool header = std::none_of(first.begin(), first.end(), is_number);
    layout.column_count = first.size();
    if (header) {
      layout.header_line = numbers[0];
      for (std::string_view f : first) layout.column_names.push_back(header_name(f));
      if (lines.size() >= 2) {
        first_data_line = numbers[1];
      } else if (source.at_eof()) {
        fail(numbers[0], 0, "header row but no data rows");
      }
    } else {
      first_data_line = numbers[0];
    }
  }

  /// The streamed path: every line through ROWS, in 1 MiB blocks. Returns the kept rows.
  std::int64_t read_streamed(SequentialRows& rows, const ProgressCallback& progress,
                             std::vector<std::vector<double>>& values) {
    // Only while this call runs: the callback is the caller's.
    struct ProgressScope {
      LineSource& source;
      ~ProgressScope() { source.set_progress(nullptr); }
    } progress_scope{source};
    if (progress) source.set_progress(&progress);
    if (source.size_hint() > 0 && mean_line_bytes > 0.0) {
      const double estimate = static_cast<double>(source.size_hint()) / mean_line_bytes;
      const auto count = static_cast<std::size_t>(
          std::min(estimate * 1.02 + 16.0, static_cast<double>(source.size_hint() / 2 + 16)));
      for (auto& v : values) reserve_huge_pages(v, count);
    }
    std::string_view line;
    while (source.next(line)) {
      if (!rows.take(line, source.line_number())) continue;
      const std::vector<double>& row = rows.values();
      for (std::size_t s = 0; s < values.size(); ++s) values[s].push_back(row[s]);
    }
    return rows.kept();
  }

  /// The mapped path. Lines up to the first kept row go through ROWS in this thread (that row
  /// is the origin of relative columns); the rest is cut into chunks at line ends. Pass 1
  /// counts each chunk's lines, which bounds its rows and fixes where its slice of the output
  /// starts; pass 2 parses the chunks in parallel straight into the output columns; then the
  /// slices are closed up over skipped lines in file order. Returns the kept rows.
  std::int64_t read_mapped(const MappedText& text, const ReadPlan& plan, SequentialRows& rows,
                           const Origin& origin, unsigned threads, std::size_t chunk_bytes,
                           const ProgressCallback& progress,
                           std::vector<std::vector<double>>& values, TableData& data) {
    const char* p = text.begin();
    std::int64_t line_no = 0;
    std::vector<double> first_row;
    while (p != text.end()) {
      std::string_view line = cut_line(p, text.end());
      ++line_no;
      if (line_too_long(line)) {
        rows.fail({RowProblem::kLineTooLong, 0, 0, 0, 0, {}}, line_no);
      }
      strip_cr(line);
      if (line_no == 1 && line.substr(0, kUtf8Bom.size()) == kUtf8Bom) {
        line.remove_prefix(kUtf8Bom.size());
      }
      if (rows.take(line, line_no)) {
        first_row = rows.values();
        break;
      }
    }
    if (rows.kept() == 0) return 0;

    // Chunks of the rest, each ending after a newline.
    const char* const region = p;
    const auto region_bytes = static_cast<std::size_t>(text.end() - region);
    if (chunk_bytes == 0) {
      constexpr std::size_t kMinChunk = std::size_t{1} << 20;
      constexpr std::size_t kMaxChunk = std::size_t{64} << 20;
      // Several chunks per thread: the load balances and progress moves.
      chunk_bytes = std::clamp(region_bytes / (std::size_t{8} * threads), kMinChunk, kMaxChunk);
    }
    std::vector<Chunk> chunks;
    for (const char* b = region; b != text.end();) {
      const char* e = text.end();
      if (static_cast<std::size_t>(text.end() - b) > chunk_bytes) {
        const char* cut = b + chunk_bytes;
        const auto* nl = static_cast<const char*>(
            std::memchr(cut - 1, '\n', static_cast<std::size_t>(text.end() - (cut - 1))));
        if (nl != nullptr) e = nl + 1;
      }
      chunks.push_back(Chunk{});
      chunks.back().begin = b;
      chunks.back().end = e;
      b = e;
    }

    // Pass 1: lines per chunk (a final line without a newline counts too).
    const auto nothing = [] {};
    parallel_for(
        chunks.size(), threads,
        [&](std::size_t i) {
          Chunk& c = chunks[i];
          c.lines = count_newlines(c.begin, c.end) + (c.end[-1] != '\n' ? 1 : 0);
          text.release(c.begin, c.end);
        },
        nothing);
    // A kept row has all its fields, the requested ones not empty, and a line end (but the
    // last): a chunk of B bytes holds at most (B + 1) / (that + 1) of them. This caps the
    // output reserved for files of mostly blank or comment lines.
    const std::size_t min_row_bytes = plan.column_count - 1 + plan.slot_count();
    std::size_t bound = 1;  // row 0 is the first kept row
    std::int64_t lines_before = line_no;
    for (Chunk& c : chunks) {
      const auto bytes = static_cast<std::size_t>(c.end - c.begin);
      c.lines_before = lines_before;
      c.row_begin = bound;
      c.row_capacity =
          std::min(static_cast<std::size_t>(c.lines), (bytes + 1) / (min_row_bytes + 1));
      lines_before += c.lines;
      bound += c.row_capacity;
    }
    std::vector<double*> out(values.size());
    for (std::size_t s = 0; s < values.size(); ++s) {
      reserve_huge_pages(values[s], bound);
      values[s].resize(bound);
      values[s][0] = first_row[s];
      out[s] = values[s].data();
    }

    // Pass 2: parse. Progress counts the bytes of finished chunks, reported by this thread.
    const auto total = static_cast<std::int64_t>(text.size());
    std::atomic<std::int64_t> done{static_cast<std::int64_t>(region - text.begin())};
    std::atomic<std::size_t> first_failed{chunks.size()};
    parallel_for(
        chunks.size(), threads,
        [&](std::size_t i) {
          Chunk& c = chunks[i];
          if (first_failed.load() > i) {
            parse_chunk(plan, origin, c, i, out, first_failed);
            text.release(c.begin, c.end);
          }
          done.fetch_add(c.end - c.begin);
        },
        [&] { report_progress(progress, "reading", done.load(), total); });

    if (first_failed.load() < chunks.size()) {
      const Chunk& c = chunks[first_failed.load()];
      rows.fail(c.error, c.lines_before + c.error.line);
    }

    // Close the slices up in file order; in a file without skipped lines nothing moves.
    std::size_t kept = 1;
    for (const Chunk& c : chunks) {
      if (c.kept > 0 && c.row_begin != kept) {
        for (std::vector<double>& v : values) {
          std::memmove(v.data() + kept, v.data() + c.row_begin, c.kept * sizeof(double));
        }
      }
      for (const LineRun& run : c.runs) {
        data.lines.add_run(static_cast<std::int64_t>(kept) + run.row, c.lines_before + run.line,
                           run.count);
      }
      data.rows_dropped += c.rows_dropped;
      data.non_finite_dropped += c.non_finite_dropped;
      kept += c.kept;
    }
    for (std::vector<double>& v : values) v.resize(kept);
    report_progress(progress, "reading", total, total);
    return static_cast<std::int64_t>(kept);
  }
};

TableReader::TableReader(std::string path, Delimiter delimiter)
    : impl_(std::make_unique<Impl>(std::move(path))) {
  impl_->sniff(delimiter);
}

TableReader::~TableReader() = default;

const TableLayout& TableReader::layout() const { return impl_->layout; }

std::optional<std::size_t> TableReader::find_column(std::string_view selector) const {
  const TableLayout& layout = impl_->layout;
  for (std::size_t i = 0; i < layout.column_names.size(); ++i) {
    if (layout.column_names[i] == selector) return i;
  }
  std::size_t index = 0;
  const auto [p, ec] = std::from_chars(selector.data(), selector.data() + selector.size(), index);
  if (ec == std::errc() && p == selector.data() + selector.size() && index >= 1 &&
      index <= layout.column_count) {
    return index - 1;
  }
  return std::nullopt;
}

std::size_t TableReader::resolve_column(std::string_view selector) const {
  if (const auto found = find_column(selector)) return *found;
  const TableLayout& layout = impl_->layout;
  const bool numeric =
      !selector.empty() &&
      std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; });
  std::string what;
  if (numeric) {
    what = "column index " + show(selector) + " out of range: the file has " +
           std::to_string(layout.column_count) + " column(s), indices start at 1";
  } else {
    what = "unknown column '" + show(selector) + "'";
  }
  what += " (available columns: " + layout.describe_columns() + ")";
  impl_->fail(layout.header_line, 0, what);
}

TableData TableReader::read(std::span<const ColumnRequest> columns, bool drop_non_finite,
                            const ProgressCallback& progress, const ReadParallelism& parallelism) {
  Impl& im = *impl_;
  if (im.consumed) throw std::logic_error("TableReader::read called twice");
  im.consumed = true;
  const TableLayout& layout = im.layout;

  // slot_of[column] = output slot or -1; a column requested twice is parsed once.
  ReadPlan plan;
  plan.column_count = layout.column_count;
  plan.delimiter = layout.delimiter;
  plan.separator = delimiter_char(layout.delimiter);
  plan.drop_non_finite = drop_non_finite;
  plan.slot_of.assign(plan.column_count, -1);
  std::vector<std::size_t> output_slot(columns.size());
  for (std::size_t r = 0; r < columns.size(); ++r) {
    const ColumnRequest& req = columns[r];
    if (req.index >= plan.column_count) throw std::out_of_range("TableReader::read: column index");
    int& slot = plan.slot_of[req.index];
    if (slot < 0) {
      slot = static_cast<int>(plan.relative.size());
      plan.relative.push_back(req.relative_to_first);
    } else if (static_cast<bool>(plan.relative[static_cast<std::size_t>(slot)]) !=
               req.relative_to_first) {
      throw std::invalid_argument("TableReader::read: column requested both relative and not");
    }
    output_slot[r] = static_cast<std::size_t>(slot);
  }
  const std::size_t nslots = plan.slot_count();

  TableData data;
  std::vector<std::vector<double>> values(nslots);
  Origin origin(nslots);
  const std::string count_origin =
      layout.has_header()
          ? "as in the header on line " + std::to_string(layout.header_line)
          : "as in the first data row on line " + std::to_string(im.first_data_line);
  SequentialRows rows(plan, layout, layout.header_line, count_origin, data, origin);

  MappedText mapped;
  const bool use_mapping = im.source.size_hint() > 0 &&
                           im.source.size_hint() >= parallelism.min_mapped_bytes &&
                           mapped.map(im.source.fd());
  std::int64_t kept = 0;
  if (use_mapping) {
    const unsigned threads = resolve_threads(parallelism.threads);
    // Whatever was parsed from a file that shrank meanwhile is not its content: that is the
    // error, even when the zeros read past its end made a row fail first.
    const auto shrank = [&] {
      im.fail(0, 0,
              "the file shrank while it was read (it had " + std::to_string(mapped.size()) +
                  " bytes when opened); read it again once nothing writes to it");
    };
    try {
      kept = im.read_mapped(mapped, plan, rows, origin, threads, parallelism.chunk_bytes, progress,
                            values, data);
    } catch (...) {
      if (mapped.truncated()) shrank();
      throw;
    }
    if (mapped.truncated()) shrank();
  } else {
    kept = im.read_streamed(rows, progress, values);
  }

  if (kept == 0) {
    if (data.rows_dropped > 0) {
      im.fail(0, 0,
              "no data rows left after dropping " + std::to_string(data.rows_dropped) +
                  " row(s) holding NaN/Inf");
    }
    im.fail(layout.header_line, 0, "header row but no data rows");
  }

  data.columns.resize(columns.size());
  data.first_values.resize(columns.size());
  for (std::size_t r = 0; r < columns.size(); ++r) {
    const std::size_t s = output_slot[r];
    // Move each slot's vector to its last request; earlier duplicates get copies.
    bool last_use = true;
    for (std::size_t later = r + 1; later < columns.size(); ++later) {
      last_use = last_use && output_slot[later] != s;
    }
    data.columns[r] = last_use ? std::move(values[s]) : values[s];
    data.first_values[r] = plan.relative[s] ? origin.value[s] : data.columns[r].front();
  }
  return data;
}

// ---------------------------------------------------------------------------------------------

Series read_series(const std::string& path, const SeriesReadOptions& options) {
  TableReader reader(path, options.delimiter);
  const TableLayout& layout = reader.layout();
  std::size_t column = 0;
  if (!options.column.empty()) {
    column = reader.resolve_column(options.column);
  } else if (layout.column_count != 1) {
    throw InputError(located_message(
        path, layout.header_line, 0,
        "the file has " + std::to_string(layout.column_count) +
            " columns; choose one by name or 1-based index (--column); available columns: " +
            layout.describe_columns()));
  }
  // The time column, when asked for and the header names one in a known unit.
  std::optional<std::size_t> time_column;
  double time_factor = 1.0;
  std::string time_name;
  if (options.read_time && layout.has_header()) {
    for (const auto& [name, unit] :
         {std::pair{"time_s", TimeUnit::kSecond}, std::pair{"time_ms", TimeUnit::kMillisecond},
          std::pair{"time_us", TimeUnit::kMicrosecond},
          std::pair{"time_ns", TimeUnit::kNanosecond}}) {
      const auto found = reader.find_column(name);
      if (found && *found != column) {
        time_column = found;
        time_factor = si_factor(unit);
        time_name = name;
        break;
      }
    }
  }
  std::vector<ColumnRequest> requests{{column, false}};
  // Stamps relative to the first keep their digits (e.g. ns since the epoch beyond 2^53).
  if (time_column) requests.push_back({*time_column, true});
  TableData data = reader.read(requests, options.drop_non_finite, {},
                               ReadParallelism{.threads = options.threads});
  Series series;
  if (time_column) {
    series.time_column = time_name;
    series.time_s = std::move(data.columns[1]);
    for (double& t : series.time_s) t *= time_factor;
  }
  series.source_path = path;
  series.column_name = layout.has_header() && !layout.column_names[column].empty()
                           ? layout.column_names[column]
                           : "column " + std::to_string(column + 1);
  series.values = std::move(data.columns[0]);
  series.non_finite_dropped = data.non_finite_dropped;
  series.first_data_line = data.first_data_line;
  return series;
}

// ---------------------------------------------------------------------------------------------

namespace {

/// Units the project's own column names carry (what `imunoise simulate` writes).
constexpr std::array<std::pair<std::string_view, TimeUnit>, 4> kTimeNames{{
    {"time_s", TimeUnit::kSecond},
    {"time_ms", TimeUnit::kMillisecond},
    {"time_us", TimeUnit::kMicrosecond},
    {"time_ns", TimeUnit::kNanosecond},
}};
constexpr std::array<std::pair<std::string_view, GyroUnit>, 5> kGyroSuffixes{{
    {"rad_per_s", GyroUnit::kRadPerS},
    {"deg_per_s", GyroUnit::kDegPerS},
    {"deg_per_h", GyroUnit::kDegPerHour},
    {"rad", GyroUnit::kRadIncrement},
    {"deg", GyroUnit::kDegIncrement},
}};
constexpr std::array<std::pair<std::string_view, AccelUnit>, 4> kAccelSuffixes{{
    {"m_per_s2", AccelUnit::kMPerS2},
    {"g", AccelUnit::kG},
    {"mg", AccelUnit::kMilliG},
    {"m_per_s", AccelUnit::kMPerSIncrement},
}};
constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

/// A sensor group as mapped: column indices (x, y, z order) and the unit.
template <typename Unit>
struct GroupMapping {
  std::vector<std::size_t> columns;
  Unit unit{};
};

std::optional<std::size_t> header_index(const TableLayout& layout, std::string_view name) {
  for (std::size_t i = 0; i < layout.column_names.size(); ++i) {
    if (layout.column_names[i] == name) return i;
  }
  return std::nullopt;
}

/// Finds "<prefix>_x_<suffix>", "_y_", "_z_" for the first suffix present on all three axes.
template <typename Unit, std::size_t N>
std::optional<GroupMapping<Unit>> find_named_group(
    const TableLayout& layout, std::string_view prefix,
    const std::array<std::pair<std::string_view, Unit>, N>& suffixes) {
  for (const auto& [suffix, unit] : suffixes) {
    GroupMapping<Unit> group{{}, unit};
    for (std::string_view axis : kAxes) {
      const std::string name =
          std::string(prefix) + "_" + std::string(axis) + "_" + std::string(suffix);
      if (const auto index = header_index(layout, name)) group.columns.push_back(*index);
    }
    if (group.columns.size() == kAxes.size()) return group;
  }
  return std::nullopt;
}

template <typename Unit, std::size_t N>
std::optional<GroupMapping<Unit>> map_group(
    const TableReader& reader, const std::string& path, std::string_view group,
    const std::vector<std::string>& selectors, const std::optional<Unit>& unit, Unit default_unit,
    const std::array<std::pair<std::string_view, Unit>, N>& suffixes) {
  if (!selectors.empty()) {
    if (selectors.size() > 3) {
      throw InputError(located_message(path, 0, 0,
                                       std::string(group) +
                                           " columns: give 1 to 3 (x, y, z), got " +
                                           std::to_string(selectors.size())));
    }
    GroupMapping<Unit> mapping{{}, unit.value_or(default_unit)};
    for (const std::string& s : selectors) mapping.columns.push_back(reader.resolve_column(s));
    return mapping;
  }
  auto named = find_named_group(reader.layout(), group, suffixes);
  if (named && unit && *unit != named->unit) {
    throw InputError(located_message(
        path, reader.layout().header_line, 0,
        "column '" + reader.layout().column_names[named->columns[0]] + "' is in " +
            std::string(to_string(named->unit)) + " but " + std::string(group) + " unit " +
            std::string(to_string(*unit)) + " was given; map the columns explicitly"));
  }
  return named;
}

}  // namespace

pipeline::Recording read_recording(const std::string& path, const InputConfig& config,
                                   const ProgressCallback& progress, unsigned threads) {
  TableReader reader(path, config.delimiter.value_or(Delimiter::kAuto));
  const TableLayout& layout = reader.layout();

  if (config.rate_hz && !config.time_column.empty()) {
    throw InputError(located_message(path, 0, 0, "give either a time column or a rate, not both"));
  }
  if (config.rate_hz && !(std::isfinite(*config.rate_hz) && *config.rate_hz > 0.0)) {
    throw InputError(
        located_message(path, 0, 0, "the sample rate must be a positive number of Hz"));
  }

  // Time: a fixed rate, an explicit column, or a recognised name.
  std::optional<std::size_t> time_column;
  TimeUnit time_unit = config.time_unit.value_or(TimeUnit::kSecond);
  if (!config.rate_hz) {
    if (!config.time_column.empty()) {
      time_column = reader.resolve_column(config.time_column);
    } else {
      for (const auto& [name, unit] : kTimeNames) {
        if (const auto index = header_index(layout, name)) {
          time_column = index;
          break;
        }
      }
    }
    if (!time_column) {
      throw InputError(located_message(
          path, layout.header_line, 0,
          "no time column: give --time-col COL [--time-unit s|ms|us|ns] or --rate HZ (or "
          "time.column / rate_hz in the config); available columns: " +
              layout.describe_columns()));
    }
    if (!config.time_unit && *time_column < layout.column_names.size()) {
      for (const auto& [name, unit] : kTimeNames) {
        if (layout.column_names[*time_column] == name) time_unit = unit;
      }
    }
  }

  const auto gyro = map_group(reader, path, "gyro", config.gyro_columns, config.gyro_unit,
                              GyroUnit::kRadPerS, kGyroSuffixes);
  const auto accel = map_group(reader, path, "accel", config.accel_columns, config.accel_unit,
                               AccelUnit::kMPerS2, kAccelSuffixes);
  std::vector<std::size_t> extra;
  for (const ExtraColumn& e : config.extra_columns)
    extra.push_back(reader.resolve_column(e.column));
  if (!gyro && !accel && extra.empty()) {
    throw InputError(located_message(
        path, layout.header_line, 0,
        "no gyro or accel columns: map them with --gyro-cols / --accel-cols (or gyro.columns / "
        "accel.columns in the config), or name them gyro_x_rad_per_s ... accel_z_m_per_s2; "
        "available columns: " +
            layout.describe_columns()));
  }

  // One request per column; the time column first, relative so ns stamps stay exact.
  std::vector<ColumnRequest> requests;
  if (time_column) requests.push_back({*time_column, true});
  const std::size_t first_channel_request = requests.size();
  if (gyro) {
    for (std::size_t c : gyro->columns) requests.push_back({c, false});
  }
  if (accel) {
    for (std::size_t c : accel->columns) requests.push_back({c, false});
  }
  for (std::size_t c : extra) requests.push_back({c, false});
  for (std::size_t r = first_channel_request; time_column && r < requests.size(); ++r) {
    if (requests[r].index == *time_column) {
      throw InputError(located_message(path, layout.header_line, 0,
                                       layout.column_label(*time_column) +
                                           " is mapped both as the time column and as a channel"));
    }
  }

  TableData data = reader.read(requests, config.drop_non_finite.value_or(false), progress,
                               ReadParallelism{.threads = threads});
  const std::size_t n = data.columns.front().size();

  pipeline::Recording rec;
  rec.source_path = path;
  pipeline::SamplingOptions options;
  options.line_of_sample = [&data](std::size_t i) { return data.lines.line_of(i); };
  pipeline::TimingReport timing;
  if (time_column) {
    pipeline::require_min_samples(path, n, 2, "a sample rate from time stamps");
    const double factor = si_factor(time_unit);
    rec.time_s = std::move(data.columns[0]);
    for (double& t : rec.time_s) t *= factor;
    rec.start_time_s = data.first_values[0] * factor;
    timing = pipeline::analyze_timing(rec.time_s, options);
    if (!(timing.median_interval_s > 0.0)) {
      throw InputError(located_message(path, data.first_data_line, 0,
                                       "cannot estimate the sample rate: the time stamps never "
                                       "increase"));
    }
    rec.sample_period_s = timing.median_interval_s;
  } else {
    rec.sample_period_s = 1.0 / *config.rate_hz;
    timing = pipeline::fixed_rate_timing(*config.rate_hz, static_cast<std::int64_t>(n));
  }

  std::size_t next = first_channel_request;
  const auto add_channel = [&](std::string name, std::string unit, std::string source_unit,
                               double factor, bool increments) {
    const std::size_t column = requests[next].index;
    pipeline::Channel ch;
    ch.name = std::move(name);
    ch.unit = std::move(unit);
    ch.source_unit = std::move(source_unit);
    ch.source_column = layout.has_header() && !layout.column_names[column].empty()
                           ? layout.column_names[column]
                           : "column " + std::to_string(column + 1);
    ch.from_increments = increments;
    ch.values = std::move(data.columns[next]);
    if (factor != 1.0) {
      for (double& v : ch.values) v *= factor;
    }
    rec.channels.push_back(std::move(ch));
    ++next;
  };
  if (gyro) {
    const bool inc = is_increment(gyro->unit);
    const double factor = si_factor(gyro->unit) / (inc ? rec.sample_period_s : 1.0);
    for (std::size_t a = 0; a < gyro->columns.size(); ++a) {
      add_channel("gyro_" + std::string(kAxes[a]), "rad/s", std::string(to_string(gyro->unit)),
                  factor, inc);
    }
  }
  if (accel) {
    const bool inc = is_increment(accel->unit);
    const double factor = si_factor(accel->unit) / (inc ? rec.sample_period_s : 1.0);
    for (std::size_t a = 0; a < accel->columns.size(); ++a) {
      add_channel("accel_" + std::string(kAxes[a]), "m/s^2", std::string(to_string(accel->unit)),
                  factor, inc);
    }
  }
  for (const ExtraColumn& e : config.extra_columns) add_channel(e.name, "", "", 1.0, false);

  rec.report.samples = static_cast<std::int64_t>(n);
  rec.report.timing = timing;
  rec.report.non_finite_dropped = data.non_finite_dropped;
  rec.report.rows_dropped = data.rows_dropped;
  rec.report.channels = pipeline::check_channels(rec.channels, config.gyro_full_scale_rad_per_s,
                                                 config.accel_full_scale_m_per_s2, options);
  return rec;
}

}  // namespace imunoise::io
