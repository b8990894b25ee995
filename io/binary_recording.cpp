#include "io/binary_recording.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <utility>

#include "common/errors.h"
#include "common/huge_pages.h"
#include "common/parallel_for.h"
#include "common/sensor_kind.h"
#include "io/atomic_output.h"
#include "io/sampling_report.h"

namespace imunoise::io {

static_assert(std::endian::native == std::endian::little,
              "the binary recording format is little-endian; add byte swapping for this host");

namespace {

using Json = nlohmann::ordered_json;

constexpr std::uint64_t kExponentMask = 0x7FF0000000000000ULL;  // all ones: NaN or Inf
constexpr std::size_t kCopyChunkValues = std::size_t{1} << 17;  // 1 MiB of doubles
constexpr const char* kTimeColumnName = "time_s";

/// PATH: byte N: MESSAGE.
InputError byte_error(const std::string& path, std::uint64_t offset, const std::string& message) {
  return InputError(path + ": byte " + std::to_string(offset) + ": " + message);
}

/// PATH: header key KEY: MESSAGE.
InputError key_error(const std::string& path, const std::string& key, const std::string& message) {
  return InputError(path + ": header key '" + key + "': " + message);
}

std::uint64_t align_up(std::uint64_t x) {
  return (x + kBinaryAlignment - 1) / kBinaryAlignment * kBinaryAlignment;
}

bool is_finite_bits(double v) {
  return (std::bit_cast<std::uint64_t>(v) & kExponentMask) != kExponentMask;
}

std::string describe_non_finite(double v) { return std::isnan(v) ? "NaN" : "Inf"; }

/// The kind a standard channel must have; nullopt for extra channels.
std::optional<SensorKind> standard_kind(std::string_view name) {
  for (std::size_t c = 0; c < pipeline::kImuChannelNames.size(); ++c) {
    if (name == pipeline::kImuChannelNames[c]) return pipeline::kImuChannelKinds[c];
  }
  return std::nullopt;
}

/// Checks what the reader requires of a header; throws via MAKE_ERROR(key, message).
/// UNIT_TEXTS: the `unit` of each channel as the file spells it (empty for a header built in
/// memory, whose kinds need no parse).
template <class MakeError>
void validate_header(const BinaryRecordingHeader& h, MakeError&& make_error,
                     std::span<const std::string> unit_texts = {}) {
  if (!(std::isfinite(h.sample_period_s) && h.sample_period_s > 0.0)) {
    throw make_error("sample_period_s", "must be a finite number > 0");
  }
  if (!std::isfinite(h.start_time_s)) throw make_error("start_time_s", "must be finite");
  if (h.has_time == h.rate_hz.has_value()) {
    throw make_error("rate_hz", h.has_time ? "must be absent when has_time is true"
                                           : "is required when has_time is false");
  }
  if (h.rate_hz && !(std::isfinite(*h.rate_hz) && *h.rate_hz > 0.0)) {
    throw make_error("rate_hz", "must be a finite number > 0");
  }
  if (h.channels.empty()) throw make_error("channels", "at least one channel is required");
  if (h.sample_count == 0) throw make_error("sample_count", "must be at least 1");
  if (h.non_finite_dropped < 0) throw make_error("non_finite_dropped", "must be >= 0");
  if (h.rows_dropped < 0) throw make_error("rows_dropped", "must be >= 0");
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < h.channels.size(); ++i) {
    const pipeline::Channel& c = h.channels[i];
    const std::string where = "channels[" + std::to_string(i) + "]";
    if (c.name.empty()) throw make_error(where + ".name", "must not be empty");
    if (c.name == kTimeColumnName) {
      throw make_error(where + ".name", "'time_s' is the time column, not a channel name");
    }
    if (!names.insert(c.name).second) {
      throw make_error(where + ".name", "duplicate channel name '" + c.name + "'");
    }
    if (i < unit_texts.size() && !unit_texts[i].empty() && !parse_si_rate_unit(unit_texts[i])) {
      throw make_error(where + ".unit", "unknown unit '" + unit_texts[i] +
                                            "' (expected \"rad/s\", \"m/s^2\" or \"\")");
    }
    if (const auto kind = standard_kind(c.name); kind && c.kind != *kind) {
      throw make_error(where + ".unit", "channel '" + c.name + "' must be in \"" +
                                            std::string(si_rate_unit(*kind)) + "\", not \"" +
                                            std::string(c.unit()) + "\"");
    }
  }
}

Json header_json(const BinaryRecordingHeader& h) {
  Json j;
  j["created_by"] = h.created_by;
  j["source_path"] = h.source_path;
  j["sample_count"] = h.sample_count;
  j["sample_period_s"] = h.sample_period_s;
  if (h.rate_hz) j["rate_hz"] = *h.rate_hz;
  j["has_time"] = h.has_time;
  j["start_time_s"] = h.start_time_s;
  j["non_finite_dropped"] = h.non_finite_dropped;
  j["rows_dropped"] = h.rows_dropped;
  Json channels = Json::array();
  for (const pipeline::Channel& c : h.channels) {
    channels.push_back(Json{{"name", c.name},
                            {"unit", c.unit()},
                            {"source_column", c.source_column},
                            {"source_unit", c.source_unit},
                            {"from_increments", c.from_increments}});
  }
  j["channels"] = std::move(channels);
  return j;
}

/// Typed access to the keys of one JSON object; unknown keys are refused by finish().
class ObjectReader {
 public:
  ObjectReader(const std::string& path, const Json& object, std::string prefix)
      : path_(path), object_(object), prefix_(std::move(prefix)) {}

  const Json& require(const char* key) {
    seen_.insert(key);
    const auto it = object_.find(key);
    if (it == object_.end()) throw key_error(path_, prefix_ + key, "missing");
    return *it;
  }
  const Json* optional(const char* key) {
    seen_.insert(key);
    const auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  std::string text(const char* key) {
    const Json& v = require(key);
    if (!v.is_string()) throw key_error(path_, prefix_ + key, "expected a string");
    return v.get<std::string>();
  }
  bool boolean(const char* key) {
    const Json& v = require(key);
    if (!v.is_boolean()) throw key_error(path_, prefix_ + key, "expected true or false");
    return v.get<bool>();
  }
  double number(const char* key) { return number_of(require(key), key); }
  double number_of(const Json& v, const char* key) {
    if (!v.is_number()) throw key_error(path_, prefix_ + key, "expected a number");
    return v.get<double>();
  }
  std::uint64_t count(const Json& v, const char* key) {
    if (!v.is_number_unsigned()) {
      throw key_error(path_, prefix_ + key, "expected a non-negative integer");
    }
    return v.get<std::uint64_t>();
  }
  std::int64_t optional_count(const char* key) {
    const Json* v = optional(key);
    if (v == nullptr) return 0;
    const std::uint64_t n = count(*v, key);
    if (n > static_cast<std::uint64_t>(INT64_MAX)) {
      throw key_error(path_, prefix_ + key, "too large");
    }
    return static_cast<std::int64_t>(n);
  }
  void finish() const {
    for (const auto& [key, value] : object_.items()) {
      if (seen_.count(key) == 0) throw key_error(path_, prefix_ + key, "unknown key");
    }
  }

 private:
  const std::string& path_;
  const Json& object_;
  std::string prefix_;
  std::set<std::string> seen_;
};

BinaryRecordingHeader parse_header_json(const std::string& path, const std::string& text) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::parse_error& e) {
    // e.byte is 1-based within the header text.
    const std::uint64_t at = kBinaryPreambleBytes + (e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    if (const auto pos = what.find("syntax error"); pos != std::string::npos) {
      what = what.substr(pos);
    }
    throw byte_error(path, at, "malformed JSON header: " + what);
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range for a number beyond double range (1e999)
    throw byte_error(path, kBinaryPreambleBytes, std::string("malformed JSON header: ") + e.what());
  }
  if (!j.is_object()) {
    throw byte_error(path, kBinaryPreambleBytes, "the JSON header must be an object");
  }
  BinaryRecordingHeader h;
  ObjectReader top(path, j, "");
  h.created_by = top.text("created_by");
  h.source_path = top.text("source_path");
  h.sample_count = top.count(top.require("sample_count"), "sample_count");
  h.sample_period_s = top.number("sample_period_s");
  if (const Json* rate = top.optional("rate_hz")) h.rate_hz = top.number_of(*rate, "rate_hz");
  h.has_time = top.boolean("has_time");
  h.start_time_s = top.number("start_time_s");
  h.non_finite_dropped = top.optional_count("non_finite_dropped");
  h.rows_dropped = top.optional_count("rows_dropped");
  const Json& channels = top.require("channels");
  if (!channels.is_array()) throw key_error(path, "channels", "expected an array");
  std::vector<std::string> unit_texts;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::string prefix = "channels[" + std::to_string(i) + "].";
    if (!channels[i].is_object()) {
      throw key_error(path, prefix.substr(0, prefix.size() - 1), "expected an object");
    }
    ObjectReader ch(path, channels[i], prefix);
    pipeline::Channel c;
    c.name = ch.text("name");
    unit_texts.push_back(ch.text("unit"));
    c.kind = parse_si_rate_unit(unit_texts.back());  // other text: refused by validate_header
    c.source_column = ch.text("source_column");
    c.source_unit = ch.text("source_unit");
    c.from_increments = ch.boolean("from_increments");
    ch.finish();
    h.channels.push_back(std::move(c));
  }
  top.finish();
  validate_header(
      h,
      [&](const std::string& key, const std::string& message) {
        return key_error(path, key, message);
      },
      unit_texts);
  return h;
}

/// An open file descriptor, closed on scope exit.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

/// Reads exactly SIZE bytes at OFFSET (the caller checked they exist).
void read_exact(const std::string& path, int fd, std::uint64_t offset, void* out,
                std::size_t size) {
  auto* p = static_cast<char*>(out);
  while (size > 0) {
    const ssize_t got = ::pread(fd, p, size, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      throw byte_error(path, offset,
                       got == 0 ? "unexpected end of file"
                                : std::string("read failed (") + std::strerror(errno) + ")");
    }
    p += got;
    offset += static_cast<std::uint64_t>(got);
    size -= static_cast<std::size_t>(got);
  }
}

struct OpenedFile {
  BinaryRecordingHeader header;
  BinaryLayout layout;
};

/// Validates the preamble, header and exact file size of the open file FD.
OpenedFile read_and_check_header(const std::string& path, int fd) {
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    throw InputError(path + ": cannot stat (" + std::string(std::strerror(errno)) + ")");
  }
  if (!S_ISREG(st.st_mode)) throw InputError(path + ": not a regular file");
  const auto file_size = static_cast<std::uint64_t>(st.st_size);

  std::array<unsigned char, kBinaryPreambleBytes> pre{};
  const std::size_t have = static_cast<std::size_t>(std::min<std::uint64_t>(file_size, pre.size()));
  if (have > 0) read_exact(path, fd, 0, pre.data(), have);
  const std::size_t magic_bytes = std::min(have, kBinaryMagic.size());
  if (magic_bytes < kBinaryMagic.size() ||
      !std::equal(kBinaryMagic.begin(), kBinaryMagic.end(), pre.begin())) {
    throw byte_error(path, 0,
                     "not an imunoise binary recording (bad magic; expected 89 49 4D 4E 42 0D 0A "
                     "1A)");
  }
  if (file_size < kBinaryPreambleBytes) {
    throw byte_error(
        path, file_size,
        "file ends inside the 24-byte preamble (" + std::to_string(file_size) + " bytes)");
  }
  std::uint32_t version = 0;
  std::uint32_t reserved = 0;
  std::uint64_t header_bytes = 0;
  std::memcpy(&version, pre.data() + 8, 4);
  std::memcpy(&reserved, pre.data() + 12, 4);
  std::memcpy(&header_bytes, pre.data() + 16, 8);
  if (version != kBinaryFormatVersion) {
    throw byte_error(path, 8,
                     "format version " + std::to_string(version) +
                         " is not supported (this imunoise reads version " +
                         std::to_string(kBinaryFormatVersion) + ")");
  }
  if (reserved != 0) throw byte_error(path, 12, "reserved field must be 0");
  if (header_bytes > file_size - kBinaryPreambleBytes) {
    throw byte_error(path, 16,
                     "JSON header length " + std::to_string(header_bytes) +
                         " runs past the end of the file (" + std::to_string(file_size) +
                         " bytes)");
  }
  if (header_bytes > kBinaryMaxHeaderBytes) {
    throw byte_error(path, 16,
                     "JSON header length " + std::to_string(header_bytes) + " exceeds the " +
                         std::to_string(kBinaryMaxHeaderBytes) + "-byte limit");
  }
  std::string text(static_cast<std::size_t>(header_bytes), '\0');
  if (header_bytes > 0) read_exact(path, fd, kBinaryPreambleBytes, text.data(), text.size());

  OpenedFile opened;
  opened.header = parse_header_json(path, text);
  const BinaryRecordingHeader& h = opened.header;
  const auto layout = binary_layout(header_bytes, h.sample_count, h.column_count());
  if (!layout) {
    throw key_error(path, "sample_count",
                    std::to_string(h.sample_count) + " samples × " +
                        std::to_string(h.column_count()) + " columns overflow 64-bit sizes");
  }
  if (layout->file_size != file_size) {
    const std::string expected = std::to_string(layout->file_size);
    throw InputError(path + ": file size " + std::to_string(file_size) +
                     " bytes, but the header (" + std::to_string(h.sample_count) + " samples × " +
                     std::to_string(h.column_count()) + " columns) implies exactly " + expected +
                     " bytes (" +
                     (file_size < layout->file_size ? "truncated data" : "trailing bytes") + ")");
  }
  // Padding before the data must be zero.
  const std::uint64_t pad_start = kBinaryPreambleBytes + header_bytes;
  std::array<unsigned char, kBinaryAlignment> pad{};
  const auto pad_size = static_cast<std::size_t>(layout->data_offset - pad_start);
  if (pad_size > 0) read_exact(path, fd, pad_start, pad.data(), pad_size);
  for (std::size_t i = 0; i < pad_size; ++i) {
    if (pad[i] != 0) throw byte_error(path, pad_start + i, "padding after the header must be 0");
  }
  opened.layout = *layout;
  return opened;
}

}  // namespace

std::optional<BinaryLayout> binary_layout(std::uint64_t header_bytes, std::uint64_t sample_count,
                                          std::uint64_t column_count) {
  constexpr std::uint64_t kMax = UINT64_MAX - kBinaryAlignment;
  BinaryLayout layout;
  std::uint64_t column_bytes = 0;
  if (header_bytes > kMax - kBinaryPreambleBytes) return std::nullopt;
  layout.data_offset = align_up(kBinaryPreambleBytes + header_bytes);
  if (__builtin_mul_overflow(sample_count, std::uint64_t{8}, &column_bytes) ||
      column_bytes > kMax) {
    return std::nullopt;
  }
  layout.column_stride = align_up(column_bytes);
  std::uint64_t data_bytes = 0;
  if (__builtin_mul_overflow(layout.column_stride, column_count, &data_bytes) ||
      __builtin_add_overflow(layout.data_offset, data_bytes, &layout.file_size) ||
      layout.file_size > static_cast<std::uint64_t>(INT64_MAX)) {
    return std::nullopt;
  }
  return layout;
}

BinaryRecordingHeader binary_header_of(const pipeline::Recording& recording) {
  BinaryRecordingHeader h;
  h.source_path = recording.source_path;
  h.created_by = std::string(kBinaryCreatedBy);
  h.sample_period_s = recording.sample_period_s;
  h.has_time = !recording.time_s.empty();
  if (!h.has_time) {
    const double rate = recording.report.timing.rate_hz;
    h.rate_hz = rate > 0.0 ? rate : 1.0 / recording.sample_period_s;
  }
  h.start_time_s = recording.start_time_s;
  h.sample_count = recording.sample_count();
  h.non_finite_dropped = recording.report.non_finite_dropped;
  h.rows_dropped = recording.report.rows_dropped;
  for (const pipeline::Channel& c : recording.channels) {
    h.channels.push_back(
        pipeline::Channel{c.name, c.kind, {}, c.source_column, c.source_unit, c.from_increments});
  }
  return h;
}

// ---- writer ----

struct BinaryRecordingWriter::Impl {
  AtomicOutputFile file;
  BinaryRecordingHeader header;
  BinaryLayout layout;
  std::vector<std::uint64_t> written;  // samples per column

  Impl(std::string path, BinaryRecordingHeader h) : file(std::move(path)), header(std::move(h)) {}

  std::string column_name(std::size_t column) const {
    if (header.has_time && column == 0) return kTimeColumnName;
    return header.channels[column - (header.has_time ? 1 : 0)].name;
  }
};

BinaryRecordingWriter::BinaryRecordingWriter(std::string path, BinaryRecordingHeader header) {
  validate_header(header, [&](const std::string& key, const std::string& message) {
    return InputError(path + ": cannot write a binary recording: " + key + " " + message);
  });
  std::string text;
  try {
    text = header_json(header).dump(-1, ' ', false, nlohmann::json::error_handler_t::strict);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": cannot write a binary recording header: " + e.what());
  }
  const auto layout = binary_layout(text.size(), header.sample_count, header.column_count());
  if (!layout || text.size() > kBinaryMaxHeaderBytes) {
    throw InputError(path + ": cannot write a binary recording: the sizes overflow");
  }
  impl_ = std::make_unique<Impl>(std::move(path), std::move(header));
  impl_->layout = *layout;
  impl_->written.assign(impl_->header.column_count(), 0);
  std::ostream& out = impl_->file.stream();
  const std::uint32_t version = kBinaryFormatVersion;
  const std::uint32_t reserved = 0;
  const std::uint64_t header_bytes = text.size();
  out.write(reinterpret_cast<const char*>(kBinaryMagic.data()), kBinaryMagic.size());
  out.write(reinterpret_cast<const char*>(&version), sizeof version);
  out.write(reinterpret_cast<const char*>(&reserved), sizeof reserved);
  out.write(reinterpret_cast<const char*>(&header_bytes), sizeof header_bytes);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  const std::array<char, kBinaryAlignment> zeros{};
  out.write(zeros.data(),
            static_cast<std::streamsize>(layout->data_offset - kBinaryPreambleBytes - text.size()));
}

BinaryRecordingWriter::~BinaryRecordingWriter() = default;

void BinaryRecordingWriter::append(std::size_t column, std::span<const double> values) {
  Impl& w = *impl_;
  const std::string& path = w.file.target_path();
  if (column >= w.written.size()) {
    throw std::invalid_argument("BinaryRecordingWriter::append: no column " +
                                std::to_string(column));
  }
  if (values.size() > w.header.sample_count - w.written[column]) {
    throw std::invalid_argument("BinaryRecordingWriter::append: more samples than sample_count");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!is_finite_bits(values[i])) {
      throw InputError(path + ": cannot write " + describe_non_finite(values[i]) + " (" +
                       w.column_name(column) + " sample " + std::to_string(w.written[column] + i) +
                       "); binary recordings hold finite values only");
    }
  }
  if (w.header.has_time && column == 0 && w.written[0] == 0 && !values.empty() &&
      values[0] != 0.0) {
    throw InputError(path + ": cannot write a binary recording: time_s must start at 0 (got " +
                     std::to_string(values[0]) + ")");
  }
  std::ostream& out = w.file.stream();
  const std::uint64_t offset = w.layout.column_offset(column) + w.written[column] * 8;
  if (static_cast<std::uint64_t>(out.tellp()) != offset) {
    out.seekp(static_cast<std::streamoff>(offset));
  }
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(double)));
  w.written[column] += values.size();
}

void BinaryRecordingWriter::commit() {
  Impl& w = *impl_;
  std::ostream& out = w.file.stream();
  const std::array<char, kBinaryAlignment> zeros{};
  for (std::size_t c = 0; c < w.written.size(); ++c) {
    if (w.written[c] != w.header.sample_count) {
      throw std::logic_error("BinaryRecordingWriter::commit: column " + w.column_name(c) + " has " +
                             std::to_string(w.written[c]) + " of " +
                             std::to_string(w.header.sample_count) + " samples");
    }
    const std::uint64_t end = w.layout.column_offset(c) + w.header.sample_count * 8;
    const std::uint64_t pad = w.layout.column_offset(c) + w.layout.column_stride - end;
    if (pad == 0) continue;
    out.seekp(static_cast<std::streamoff>(end));
    out.write(zeros.data(), static_cast<std::streamsize>(pad));
  }
  w.file.commit();
}

void write_binary_recording(const std::string& path, const pipeline::Recording& recording) {
  const std::size_t n = recording.sample_count();
  for (const pipeline::Channel& c : recording.channels) {
    if (c.values.size() != n) {
      throw InputError(path + ": cannot write a binary recording: channel '" + c.name + "' has " +
                       std::to_string(c.values.size()) + " samples, the first channel " +
                       std::to_string(n));
    }
  }
  if (!recording.time_s.empty() && recording.time_s.size() != n) {
    throw InputError(path + ": cannot write a binary recording: time_s has " +
                     std::to_string(recording.time_s.size()) + " samples, the channels " +
                     std::to_string(n));
  }
  BinaryRecordingWriter writer(path, binary_header_of(recording));
  std::size_t column = 0;
  if (!recording.time_s.empty()) writer.append(column++, recording.time_s);
  for (const pipeline::Channel& c : recording.channels) writer.append(column++, c.values);
  writer.commit();
}

// ---- reader ----

bool is_binary_recording_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, kBinaryMagic.size()> head{};
  if (!in.read(reinterpret_cast<char*>(head.data()), head.size())) return false;
  return head == kBinaryMagic;
}

BinaryRecordingHeader read_binary_header(const std::string& path) {
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) {
    throw InputError(path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  }
  return read_and_check_header(path, fd.get()).header;
}

pipeline::Recording read_binary_recording(const std::string& path, const BinaryReadOptions& options,
                                          const ProgressCallback& progress) {
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) {
    throw InputError(path + ": cannot open (" + std::string(std::strerror(errno)) + ")");
  }
  OpenedFile opened = read_and_check_header(path, fd.get());
  const BinaryRecordingHeader& h = opened.header;
  const BinaryLayout& layout = opened.layout;
  const auto n = static_cast<std::size_t>(h.sample_count);

  const std::uint64_t data_bytes = layout.file_size - layout.data_offset;
  std::atomic<std::uint64_t> copied{0};
  report_progress(progress, "reading", 0, static_cast<std::int64_t>(data_bytes));

  // pread straight into the final array, 1 MiB at a time, each chunk checked while it is in
  // cache: the kernel copies from the page cache, with none of the 4 KiB page faults a mapping
  // of the file costs, and a file truncated meanwhile is a short read, not a SIGBUS.
  const auto read_column = [&](std::size_t column, const std::string& name,
                               std::vector<double>& out) {
    const std::uint64_t begin = layout.column_offset(column);
    reserve_huge_pages(out, n);
    for (std::size_t i = 0; i < n; i += kCopyChunkValues) {
      const std::size_t m = std::min(kCopyChunkValues, n - i);
      out.resize(i + m);
      double* chunk = out.data() + i;
      read_exact(path, fd.get(), begin + i * 8, chunk, m * 8);
      std::uint64_t bad = 0;
      for (std::size_t k = 0; k < m; ++k) {
        bad |= static_cast<std::uint64_t>(
            (std::bit_cast<std::uint64_t>(chunk[k]) & kExponentMask) == kExponentMask);
      }
      if (bad != 0) {
        for (std::size_t k = 0; k < m; ++k) {
          if (is_finite_bits(chunk[k])) continue;
          throw byte_error(path, begin + (i + k) * 8,
                           describe_non_finite(chunk[k]) + " in " + name + " at sample " +
                               std::to_string(i + k) +
                               "; binary recordings hold finite values only");
        }
      }
    }
    const std::uint64_t end = begin + static_cast<std::uint64_t>(n) * 8;
    std::array<unsigned char, kBinaryAlignment> pad{};
    const auto pad_size = static_cast<std::size_t>(begin + layout.column_stride - end);
    if (pad_size > 0) read_exact(path, fd.get(), end, pad.data(), pad_size);
    for (std::size_t k = 0; k < pad_size; ++k) {
      if (pad[k] != 0) throw byte_error(path, end + k, "padding after " + name + " must be 0");
    }
    copied += layout.column_stride;
  };

  pipeline::Recording rec;
  rec.source_path = path;
  rec.sample_period_s = h.sample_period_s;
  rec.start_time_s = h.start_time_s;
  rec.channels = std::move(opened.header.channels);
  // Columns in parallel (each one thread's pread loop). Every column is read to its end or its
  // first error, and the error of the first column in file order wins: the same message at
  // any thread count.
  const std::size_t time_columns = h.has_time ? 1 : 0;
  const std::size_t columns = time_columns + rec.channels.size();
  std::vector<std::exception_ptr> errors(columns);
  parallel_for(
      columns, options.threads,
      [&](std::size_t column) {
        try {
          if (column < time_columns) {
            read_column(column, "'time_s'", rec.time_s);
            if (rec.time_s.front() != 0.0) {
              throw byte_error(path, layout.column_offset(0),
                               "time_s must start at 0 (time since the first sample; the first "
                               "stamp goes in start_time_s)");
            }
          } else {
            pipeline::Channel& c = rec.channels[column - time_columns];
            read_column(column, "channel '" + c.name + "'", c.values);
          }
        } catch (...) {
          errors[column] = std::current_exception();
        }
      },
      [&] {
        report_progress(progress, "reading", static_cast<std::int64_t>(copied.load()),
                        static_cast<std::int64_t>(data_bytes));
      });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  report_progress(progress, "reading", static_cast<std::int64_t>(data_bytes),
                  static_cast<std::int64_t>(data_bytes));

  // Sampling report exactly as io::read_recording builds it; the timing checks run beside
  // the channel checks (one item each, so the result does not depend on the thread count).
  const pipeline::SamplingOptions sampling;
  pipeline::TimingReport timing;
  const std::vector<pipeline::ChannelSamples> checks = pipeline::channel_checks(
      rec.channels, options.gyro_full_scale_rad_per_s, options.accel_full_scale_m_per_s2);
  rec.report.channels.resize(checks.size());
  parallel_for(checks.size() + 1, options.threads, [&](std::size_t item) {
    if (item == 0) {
      timing = h.has_time ? pipeline::analyze_timing(rec.time_s, sampling)
                          : pipeline::fixed_rate_timing(*h.rate_hz, static_cast<std::int64_t>(n));
    } else {
      rec.report.channels[item - 1] = pipeline::analyze_channel(checks[item - 1], sampling);
    }
  });
  if (h.has_time && n >= 2 && !(timing.median_interval_s > 0.0)) {
    throw byte_error(path, layout.column_offset(0),
                     "the time stamps never increase (cannot estimate the sample rate)");
  }
  if (h.has_time && timing.median_interval_s > 0.0) {
    // The analysis takes the header's period (the writer's, docs/binary-format.md), so the
    // report states that one: "from the mean" only when the header is the stamps' mean.
    timing.period_from_mean = timing.period_from_mean &&
                              std::fabs(rec.sample_period_s - timing.mean_interval_s) <=
                                  pipeline::kPeriodFromMeanThreshold * timing.median_interval_s;
    // The stamps' own rate when they give the header's period (on a decimal grid that rate is
    // exact: 400, where 1 / 0.0025 is 400 only by luck of rounding); else the header's.
    if (timing.sample_period_s != rec.sample_period_s) timing.rate_hz = 1.0 / rec.sample_period_s;
    timing.sample_period_s = rec.sample_period_s;
  }
  rec.report.samples = static_cast<std::int64_t>(n);
  rec.report.timing = std::move(timing);
  rec.report.non_finite_dropped = h.non_finite_dropped;
  rec.report.rows_dropped = h.rows_dropped;
  return rec;
}

}  // namespace imunoise::io
