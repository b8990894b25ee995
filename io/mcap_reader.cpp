/// @file
/// @brief MCAP reader (see mcap_reader.h for the format and the error contract).
#include "io/mcap_reader.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <utility>

#include "common/errors.h"
#include "io/binary_file.h"
#include "io/chunk_decompression.h"
#include "io/ros_imu_message.h"

namespace imunoise::io {
namespace {

// Record opcodes (mcap.dev/spec, "Records").
constexpr std::uint8_t kOpFooter = 0x02;
constexpr std::uint8_t kOpSchema = 0x03;
constexpr std::uint8_t kOpChannel = 0x04;
constexpr std::uint8_t kOpMessage = 0x05;
constexpr std::uint8_t kOpChunk = 0x06;
constexpr std::uint8_t kOpChunkIndex = 0x08;
constexpr std::uint8_t kOpStatistics = 0x0B;
constexpr std::uint8_t kOpDataEnd = 0x0F;

constexpr std::uint64_t kMagicBytes = 8;
constexpr std::uint64_t kRecordHead = 9;      // opcode + uint64 length
constexpr std::uint64_t kFooterContent = 20;  // summary_start, summary_offset_start, crc
constexpr std::uint64_t kMessageHead = 22;    // channel id, sequence, log and publish time
constexpr std::string_view kFileKind = "MCAP file";

using Bytes = std::span<const std::uint8_t>;

struct Channel {
  std::uint16_t id = 0;
  std::string topic;
  std::string encoding;  // message encoding: "cdr", "ros1", ...
  std::string type;      // schema name
  std::int64_t messages = 0;

  bool is_imu() const {
    return (encoding == "cdr" && type == kRos2ImuType) ||
           (encoding == "ros1" && type == kRos1ImuType);
  }
};

/// Receives the messages of a scan.
struct MessageSink {
  virtual ~MessageSink() = default;
  /// A message of CHANNEL (index into McapFile::channels()) in the record at OFFSET.
  virtual void message(std::size_t channel, std::int64_t log_time_ns, Bytes data,
                       std::uint64_t offset, const std::string& where) = 0;
};

class McapFile {
 public:
  explicit McapFile(const std::string& path) : file_(path) {
    std::vector<std::uint8_t> magic;
    file_.read_some(0, kMagicBytes, magic);
    if (std::string_view(reinterpret_cast<const char*>(magic.data()), magic.size()) != kMcapMagic) {
      file_.fail(0, "not an MCAP file (no \\x89MCAP0\\r\\n magic)");
    }
    read_summary();
  }

  const std::string& path() const { return file_.path(); }
  std::uint64_t file_size() const { return file_.size(); }
  /// True when the summary gave the channels and their message counts.
  bool has_statistics() const { return statistics_; }
  const std::vector<Channel>& channels() const { return channels_; }

  /// Scans the data section in order; a chunk whose index shows none of WANTED's channels is
  /// skipped (WANTED empty: no chunk is skipped). Messages go to SINK.
  void scan(const std::set<std::uint16_t>& wanted, MessageSink& sink) {
    std::uint64_t pos = kMagicBytes;
    while (pos < data_limit_) {
      const std::uint64_t offset = pos;
      const Bytes head = file_.view(pos, kRecordHead, "record header");
      const std::uint8_t op = head[0];
      const std::uint64_t length = load_le64(head.data() + 1);
      if (length > data_limit_ - pos - kRecordHead) {
        file_.fail(pos, "truncated record (opcode " + hex(op) + "): its content needs " +
                            std::to_string(length) + " bytes, the file has " +
                            std::to_string(data_limit_ - pos - kRecordHead) + " after its header");
      }
      pos += kRecordHead + length;
      if (op == kOpDataEnd || op == kOpFooter) break;
      if (op == kOpChunk) {
        if (!wanted.empty() && skippable(offset, wanted)) continue;
        chunk(offset, file_.view(offset + kRecordHead, length, "chunk"), sink);
        continue;
      }
      if (op != kOpSchema && op != kOpChannel && op != kOpMessage) continue;
      const Bytes content = file_.view(offset + kRecordHead, length, "record");
      record(op, content, offset, offset + kRecordHead, "", sink);
    }
  }

 private:
  static std::string hex(std::uint8_t v) {
    static constexpr char kDigits[] = "0123456789abcdef";
    return std::string("0x") + kDigits[v >> 4] + kDigits[v & 0xFu];
  }

  /// The summary through the footer; absent (the data section is then scanned to the end of
  /// the file) when the file does not end with a footer and the magic.
  void read_summary() {
    data_limit_ = file_.size();
    const std::uint64_t tail = kRecordHead + kFooterContent + kMagicBytes;
    if (file_.size() < kMagicBytes + tail) return;
    const std::uint64_t footer_at = file_.size() - tail;
    std::vector<std::uint8_t> footer;
    file_.read(footer_at, tail, footer, "footer");
    if (footer[0] != kOpFooter || load_le64(footer.data() + 1) != kFooterContent ||
        std::string_view(reinterpret_cast<const char*>(footer.data()) + tail - kMagicBytes,
                         kMagicBytes) != kMcapMagic) {
      return;  // cut short: no footer
    }
    data_limit_ = footer_at;
    const std::uint64_t summary_start = load_le64(footer.data() + kRecordHead);
    if (summary_start == 0) return;
    if (summary_start < kMagicBytes || summary_start > footer_at) {
      file_.fail(footer_at, "the footer's summary_start " + std::to_string(summary_start) +
                                " is outside the file (8 to " + std::to_string(footer_at) + ")");
    }
    data_limit_ = summary_start;
    std::vector<std::uint8_t> summary;
    file_.read(summary_start, footer_at - summary_start, summary, "summary section");
    ByteCursor cursor(summary, file_.path(), summary_start);
    std::map<std::uint16_t, std::int64_t> counts;
    NullSink none;
    while (!cursor.at_end()) {
      const std::uint64_t offset = cursor.offset();
      const std::uint8_t op = cursor.u8("summary record opcode");
      const std::uint64_t length = cursor.u64("summary record length");
      ByteCursor content(cursor.bytes(length, "summary record"), file_.path(),
                         offset + kRecordHead);
      if (op == kOpSchema || op == kOpChannel) {
        record(op, content.bytes(length, "record"), offset, offset + kRecordHead, "", none);
      } else if (op == kOpStatistics) {
        content.skip(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8, "statistics");
        ByteCursor entries(
            content.bytes(content.u32("channel_message_counts length"), "channel_message_counts"),
            file_.path(), offset);
        while (!entries.at_end()) {
          const std::uint16_t id = entries.u16("channel id");
          // The file's word: no more messages than bytes (keeps the sums of counts in range).
          counts[id] =
              static_cast<std::int64_t>(std::min(entries.u64("message count"), file_.size()));
        }
        statistics_ = true;
      } else if (op == kOpChunkIndex) {
        content.skip(16, "chunk index times");
        const std::uint64_t chunk_at = content.u64("chunk_start_offset");
        content.skip(8, "chunk_length");
        ByteCursor entries(
            content.bytes(content.u32("message_index_offsets length"), "message_index_offsets"),
            file_.path(), offset);
        std::vector<std::uint16_t>& ids = chunk_channels_[chunk_at];
        while (!entries.at_end()) {
          ids.push_back(entries.u16("channel id"));
          entries.skip(8, "message index offset");
        }
      }
    }
    if (statistics_ && channels_.empty()) statistics_ = false;  // counts without their channels
    for (Channel& c : channels_) {
      if (const auto it = counts.find(c.id); it != counts.end()) c.messages = it->second;
    }
  }

  struct NullSink : MessageSink {
    void message(std::size_t, std::int64_t, Bytes, std::uint64_t, const std::string&) override {}
  };

  /// True when the chunk at OFFSET is indexed and holds none of WANTED's channels.
  bool skippable(std::uint64_t offset, const std::set<std::uint16_t>& wanted) const {
    const auto it = chunk_channels_.find(offset);
    if (it == chunk_channels_.end() || it->second.empty()) return false;
    return std::none_of(it->second.begin(), it->second.end(),
                        [&](std::uint16_t id) { return wanted.count(id) > 0; });
  }

  void chunk(std::uint64_t offset, Bytes content, MessageSink& sink) {
    ByteCursor c(content, file_.path(), offset + kRecordHead);
    c.skip(16, "chunk message times");
    const std::uint64_t size = c.u64("chunk uncompressed_size");
    c.skip(4, "chunk uncompressed_crc");
    const std::string_view compression = c.string32("chunk compression");
    const std::uint64_t records_length = c.u64("chunk records length");
    const Bytes compressed = c.bytes(records_length, "chunk records");
    Bytes records = compressed;
    if (compression.empty()) {
      if (size != records_length) {
        file_.fail(offset, "uncompressed chunk of " + std::to_string(records_length) +
                               " bytes declares " + std::to_string(size));
      }
    } else {
      ChunkCompression kind = ChunkCompression::kNone;
      if (compression == "zstd") {
        kind = ChunkCompression::kZstd;
      } else if (compression == "lz4") {
        kind = ChunkCompression::kLz4;
      } else {
        file_.fail(offset, "unknown chunk compression " + quoted_bytes(compression) +
                               " (MCAP chunks are \"\", zstd or lz4)");
      }
      decompress_chunk(kind, compressed, size, chunk_buf_, file_.path(), offset);
      records = chunk_buf_;
    }
    std::size_t pos = 0;
    while (pos < records.size()) {
      const std::string where = " (in the chunk's records at offset " + std::to_string(pos) + ")";
      if (records.size() - pos < kRecordHead) {
        file_.fail(offset, "truncated record header" + where);
      }
      const std::uint8_t op = records[pos];
      const std::uint64_t length = load_le64(records.data() + pos + 1);
      if (length > records.size() - pos - kRecordHead) {
        file_.fail(offset, "a record of " + std::to_string(length) +
                               " bytes runs past the end of the chunk" + where);
      }
      record(op, records.subspan(pos + kRecordHead, length), offset, offset, where, sink);
      pos += kRecordHead + length;
    }
  }

  /// A schema, channel or message record's CONTENT (others are ignored); errors name OFFSET.
  void record(std::uint8_t op, Bytes content, std::uint64_t offset, std::uint64_t base,
              const std::string& where, MessageSink& sink) {
    ByteCursor c(content, file_.path(), base, where.empty() ? std::string() : where.substr(1));
    if (op == kOpMessage) {
      if (content.size() < kMessageHead) {
        file_.fail(offset, "a message record of " + std::to_string(content.size()) +
                               " bytes is shorter than its 22-byte header" + where);
      }
      const std::uint16_t id = load_le16(content.data());
      const auto it = ids_.find(id);
      if (it == ids_.end()) {
        file_.fail(offset, "a message on channel " + std::to_string(id) +
                               ", which no channel record defines before it" + where);
      }
      const auto log_time = static_cast<std::int64_t>(load_le64(content.data() + 6));
      sink.message(it->second, log_time, content.subspan(kMessageHead), offset, where);
    } else if (op == kOpSchema) {
      const std::uint16_t id = c.u16("schema id");
      schemas_[id] = std::string(c.string32("schema name"));
    } else if (op == kOpChannel) {
      Channel ch;
      ch.id = c.u16("channel id");
      const std::uint16_t schema = c.u16("channel schema_id");
      ch.topic = c.string32("channel topic");
      ch.encoding = c.string32("channel message_encoding");
      if (ids_.count(ch.id) > 0) return;  // repeated (chunks, summary)
      if (schema != 0) {
        const auto it = schemas_.find(schema);
        if (it == schemas_.end()) {
          file_.fail(offset, "channel " + std::to_string(ch.id) + " names schema " +
                                 std::to_string(schema) + ", which no schema record defines" +
                                 where);
        }
        ch.type = it->second;
      }
      ids_.emplace(ch.id, channels_.size());
      channels_.push_back(std::move(ch));
    }
  }

  BinaryFile file_;
  std::uint64_t data_limit_ = 0;
  bool statistics_ = false;
  std::map<std::uint16_t, std::string> schemas_;
  std::vector<Channel> channels_;
  std::map<std::uint16_t, std::size_t> ids_;
  std::map<std::uint64_t, std::vector<std::uint16_t>> chunk_channels_;
  std::vector<std::uint8_t> chunk_buf_;
};

std::vector<LogTopic> topics_of(const std::vector<Channel>& channels) {
  std::vector<LogTopic> topics;
  for (const Channel& c : channels) {
    auto it = std::find_if(topics.begin(), topics.end(),
                           [&](const LogTopic& t) { return t.name == c.topic; });
    if (it == topics.end()) {
      LogTopic t;
      t.name = c.topic;
      t.type = c.type.empty() ? "(no schema, " + c.encoding + ")" : c.type;
      t.is_imu = c.is_imu();
      topics.push_back(std::move(t));
      it = topics.end() - 1;
    }
    it->message_count += c.messages;
  }
  return topics;
}

/// Counts every channel's messages, and decodes the chosen topic's (the named one, or, when
/// TOPIC is empty, the first Imu topic that has a message).
class ImuSink : public MessageSink {
 public:
  /// DECODE false: count only.
  ImuSink(McapFile& file, std::string topic, const LogReadOptions& options, bool decode = true)
      : file_(file),
        topic_(std::move(topic)),
        decode_(decode),
        samples_(options, ros_imu_fields(), si_imu_units()) {}

  void message(std::size_t channel, std::int64_t log_time_ns, Bytes data, std::uint64_t offset,
               const std::string& where) override {
    ++counts_[channel];
    if (!decode_) return;
    const Channel& c = file_.channels()[channel];
    if (topic_.empty() && c.is_imu()) topic_ = c.topic;
    if (c.topic != topic_ || !c.is_imu()) return;
    const bool ok = c.encoding == "cdr" ? decode_cdr_imu(data, message_, error_)
                                        : decode_ros1_imu(data, message_, error_);
    const std::string what = "topic " + quoted_bytes(topic_) + ": ";
    if (!ok) throw_at_offset(file_.path(), offset, what + error_ + where);
    if (const std::string* bad = samples_.add(message_, log_time_ns)) {
      throw_at_offset(file_.path(), offset,
                      what + "non-finite value in " + *bad +
                          " (give --drop-non-finite to drop such messages)" + where);
    }
  }

  const std::string& topic() const { return topic_; }
  ImuSampleCollector& samples() { return samples_; }
  /// The channels with the counts of the scan.
  std::vector<Channel> counted() const {
    std::vector<Channel> out = file_.channels();
    for (std::size_t i = 0; i < out.size(); ++i) {
      const auto it = counts_.find(i);
      out[i].messages = it == counts_.end() ? 0 : it->second;
    }
    return out;
  }

 private:
  McapFile& file_;
  std::string topic_;
  bool decode_;
  ImuSampleCollector samples_;
  std::map<std::size_t, std::int64_t> counts_;
  ImuMessage message_;
  std::string error_;
};

}  // namespace

bool is_mcap_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kMagicBytes, '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) return false;
  return head == kMcapMagic;
}

std::vector<LogTopic> list_mcap_topics(const std::string& path) {
  McapFile file(path);
  if (file.has_statistics()) return topics_of(file.channels());
  ImuSink counter(file, "", {}, false);
  file.scan({}, counter);
  return topics_of(counter.counted());
}

pipeline::Recording read_mcap_imu(const std::string& path, const LogReadOptions& options) {
  McapFile file(path);
  std::set<std::uint16_t> wanted;
  std::string name = options.topic;
  std::int64_t reserve = 0;
  if (file.has_statistics()) {
    const std::vector<LogTopic> topics = topics_of(file.channels());
    const LogTopic& topic = select_imu_topic(path, topics, options, kFileKind);
    name = topic.name;
    reserve = topic.message_count;
    for (const Channel& c : file.channels()) {
      if (c.topic == name) wanted.insert(c.id);
    }
  }
  ImuSink sink(file, name, options);
  sink.samples().reserve(reserve, file.file_size());
  file.scan(wanted, sink);
  if (!file.has_statistics()) {
    // Without statistics the topics are known only now: check the choice against them all.
    (void)select_imu_topic(path, topics_of(sink.counted()), options, kFileKind);
  }
  if (sink.samples().size() == 0 && sink.topic().empty()) {
    throw InputError(located_message(path, 0, 0, "no Imu message found"));
  }
  return sink.samples().finish(path, sink.topic());
}

}  // namespace imunoise::io
