/// @file
/// @brief ROS 1 bag reader (see rosbag1_reader.h for the format and the error contract).
#include "io/rosbag1_reader.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "common/errors.h"
#include "io/binary_file.h"
#include "io/chunk_decompression.h"
#include "io/ros_imu_message.h"

namespace imunoise::io {
namespace {

// Record op codes (wiki.ros.org/Bags/Format/2.0, "Records").
constexpr std::uint8_t kOpMessageData = 0x02;
constexpr std::uint8_t kOpBagHeader = 0x03;
constexpr std::uint8_t kOpIndexData = 0x04;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpChunkInfo = 0x06;
constexpr std::uint8_t kOpConnection = 0x07;

constexpr std::string_view kFileKind = "bag";
constexpr std::uint64_t kMagicBytes = kRosbag1Magic.size();

using Bytes = std::span<const std::uint8_t>;

std::string_view text_of(Bytes b) { return {reinterpret_cast<const char*>(b.data()), b.size()}; }

/// One "name=value" field of a record header.
struct Field {
  std::string_view name;
  Bytes value;
};

/// Splits a record header into its fields. Returns an error text, empty when it parses.
std::string parse_fields(Bytes header, std::vector<Field>& fields) {
  fields.clear();
  std::size_t pos = 0;
  while (pos < header.size()) {
    if (header.size() - pos < 4) return "a record header ends inside a field length";
    const std::uint32_t length = load_le32(header.data() + pos);
    pos += 4;
    if (length > header.size() - pos) {
      return "a header field of " + std::to_string(length) + " bytes is longer than its header (" +
             std::to_string(header.size() - pos) + " bytes left)";
    }
    const Bytes field = header.subspan(pos, length);
    pos += length;
    const auto* eq = static_cast<const std::uint8_t*>(std::memchr(field.data(), '=', field.size()));
    if (eq == nullptr) return "a header field has no '=': " + quoted_bytes(text_of(field));
    const auto name_length = static_cast<std::size_t>(eq - field.data());
    fields.push_back({text_of(field.first(name_length)), field.subspan(name_length + 1)});
  }
  return {};
}

const Field* find_field(const std::vector<Field>& fields, std::string_view name) {
  for (const Field& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

/// A field of exactly SIZE bytes (1, 4 or 8), little-endian; an error text when absent or of
/// another size.
std::string integer_field(const std::vector<Field>& fields, std::string_view name, std::size_t size,
                          std::uint64_t& value) {
  const Field* f = find_field(fields, name);
  if (f == nullptr) return "the record has no '" + std::string(name) + "' field";
  if (f->value.size() != size) {
    return "field '" + std::string(name) + "' has " + std::to_string(f->value.size()) +
           " bytes, expected " + std::to_string(size);
  }
  value = size == 1   ? f->value[0]
          : size == 4 ? load_le32(f->value.data())
                      : load_le64(f->value.data());
  return {};
}

/// A record's time field (uint32 sec, uint32 nsec) in ns.
std::int64_t time_ns(Bytes value) {
  return static_cast<std::int64_t>(load_le32(value.data())) * 1'000'000'000 +
         static_cast<std::int64_t>(load_le32(value.data() + 4));
}

struct Connection {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;
  std::string md5sum;
  std::uint64_t offset = 0;  // of its first record, for errors
  std::int64_t messages = 0;
};

struct ChunkInfo {
  std::uint64_t chunk_pos = 0;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;  // connection id, messages
};

/// A record read from the file (not from a chunk).
struct FileRecord {
  std::uint64_t offset = 0;
  std::uint8_t op = 0;
  std::vector<Field> fields;  // views into the bag's header buffer
  std::uint64_t data_offset = 0;
  std::uint32_t data_length = 0;
};

/// Receives what a walk over the chunks finds.
struct ChunkVisitor {
  virtual ~ChunkVisitor() = default;
  /// A message record of connection CONN (an index into Bag::connections()).
  virtual void message(std::size_t conn, std::int64_t time_ns, Bytes data,
                       std::uint64_t chunk_offset, std::size_t offset_in_chunk) = 0;
};

class Bag {
 public:
  explicit Bag(const std::string& path) : file_(path) {
    std::vector<std::uint8_t> magic;
    file_.read_some(0, kMagicBytes, magic);
    if (text_of(magic) != kRosbag1Magic) {
      const bool other_version = text_of(magic).starts_with("#ROSBAG V");
      file_.fail(0, other_version ? "bag format " + quoted_bytes(text_of(magic).substr(9, 3)) +
                                        " is not supported (only 2.0)"
                                  : "not a ROS bag (no \"#ROSBAG V2.0\" line)");
    }
    FileRecord header;
    read_record(kMagicBytes, header, "bag header record");
    if (header.op != kOpBagHeader) {
      fail_record(header, "the first record is not the bag header (op " + op_text(header.op) + ")");
    }
    std::uint64_t index_pos = 0;
    check(header, integer_field(header.fields, "index_pos", 8, index_pos));
    records_start_ = header.data_offset + header.data_length;
    // 0 while the bag is being recorded; past the end when the file was cut after recording.
    indexed_ = index_pos >= records_start_ && index_pos < file_.size();
    if (indexed_) read_index(index_pos);
  }

  const std::string& path() const { return file_.path(); }
  std::uint64_t file_size() const { return file_.size(); }
  bool indexed() const { return indexed_; }
  const std::vector<Connection>& connections() const { return connections_; }
  const std::vector<ChunkInfo>& chunk_infos() const { return chunk_infos_; }

  /// The connection index of ID (registered on first sight), from the record at OFFSET.
  std::size_t connection(std::uint32_t id, std::string topic, Bytes data, std::uint64_t offset,
                         const std::string& where) {
    const auto it = ids_.find(id);
    if (it != ids_.end()) return it->second;
    std::string error = parse_fields(data, data_fields_);
    if (!error.empty())
      file_.fail(offset, "connection " + std::to_string(id) + where + ": " + error);
    Connection c;
    c.id = id;
    c.topic = std::move(topic);
    c.offset = offset;
    if (const Field* f = find_field(data_fields_, "type")) c.type = text_of(f->value);
    if (const Field* f = find_field(data_fields_, "md5sum")) c.md5sum = text_of(f->value);
    ids_.emplace(id, connections_.size());
    connections_.push_back(std::move(c));
    return connections_.size() - 1;
  }
  std::optional<std::size_t> find_connection(std::uint32_t id) const {
    const auto it = ids_.find(id);
    if (it == ids_.end()) return std::nullopt;
    return it->second;
  }

  /// Walks the chunks: the ones at CHUNK_POSITIONS, or (empty) every record of the file in
  /// order. Connections found in chunks are registered; every message is passed to VISITOR.
  void walk(const std::vector<std::uint64_t>& chunk_positions, ChunkVisitor& visitor) {
    if (!chunk_positions.empty()) {
      for (const std::uint64_t pos : chunk_positions) {
        FileRecord r;
        read_record(pos, r, "chunk record");
        if (r.op != kOpChunk) {
          fail_record(
              r, "the chunk info names a record that is not a chunk (op " + op_text(r.op) + ")");
        }
        chunk(r, visitor);
      }
      return;
    }
    std::uint64_t pos = records_start_;
    while (pos < file_.size()) {
      FileRecord r;
      read_record(pos, r, "record");
      switch (r.op) {
        case kOpChunk:
          chunk(r, visitor);
          break;
        case kOpConnection:
          connection_record(r);
          break;
        case kOpIndexData:
        case kOpChunkInfo:
          break;
        default:
          fail_record(r, "unexpected record op " + op_text(r.op) + " between the chunks");
      }
      pos = r.data_offset + r.data_length;
    }
  }

 private:
  static std::string op_text(std::uint8_t op) {
    static constexpr char kDigits[] = "0123456789abcdef";
    return std::string("0x") + kDigits[op >> 4] + kDigits[op & 0xFu];
  }
  [[noreturn]] void fail_record(const FileRecord& r, const std::string& problem) const {
    file_.fail(r.offset, problem);
  }
  void check(const FileRecord& r, const std::string& error) const {
    if (!error.empty()) fail_record(r, error);
  }

  /// Reads the record at POS (its header; its data stays in the file), checking every length
  /// against the file size.
  void read_record(std::uint64_t pos, FileRecord& r, std::string_view what) {
    r.offset = pos;
    const std::uint64_t left = file_.size() - pos;
    if (left < 4) {
      file_.fail(pos, "truncated " + std::string(what) + ": the file ends " + std::to_string(left) +
                          " bytes into its header length");
    }
    file_.read(pos, 4, length_buf_, what);
    const std::uint32_t header_length = load_le32(length_buf_.data());
    if (std::uint64_t{header_length} + 8 > left) {
      file_.fail(pos, "truncated " + std::string(what) + ": its header of " +
                          std::to_string(header_length) + " bytes and data length need " +
                          std::to_string(std::uint64_t{header_length} + 8) +
                          " bytes, the file has " + std::to_string(left) + " from here");
    }
    file_.read(pos + 4, std::uint64_t{header_length} + 4, header_buf_, what);
    const Bytes header = Bytes(header_buf_).first(header_length);
    check(r, parse_fields(header, r.fields));
    std::uint64_t op = 0;
    check(r, integer_field(r.fields, "op", 1, op));
    r.op = static_cast<std::uint8_t>(op);
    r.data_length = load_le32(header_buf_.data() + header_length);
    r.data_offset = pos + 8 + header_length;
    if (r.data_length > file_.size() - r.data_offset) {
      file_.fail(pos, "truncated " + std::string(what) + ": its data needs " +
                          std::to_string(r.data_length) + " bytes, the file has " +
                          std::to_string(file_.size() - r.data_offset) + " after its header");
    }
  }

  void connection_record(const FileRecord& r) {
    std::uint64_t id = 0;
    check(r, integer_field(r.fields, "conn", 4, id));
    const Field* topic = find_field(r.fields, "topic");
    if (topic == nullptr) fail_record(r, "the connection record has no 'topic' field");
    const std::string name(text_of(topic->value));
    file_.read(r.data_offset, r.data_length, data_buf_, "connection record data");
    connection(static_cast<std::uint32_t>(id), name, data_buf_, r.offset, "");
  }

  void read_index(std::uint64_t index_pos) {
    std::uint64_t pos = index_pos;
    while (pos < file_.size()) {
      FileRecord r;
      read_record(pos, r, "index record");
      if (r.op == kOpConnection) {
        connection_record(r);
      } else if (r.op == kOpChunkInfo) {
        ChunkInfo info;
        std::uint64_t count = 0;
        check(r, integer_field(r.fields, "chunk_pos", 8, info.chunk_pos));
        check(r, integer_field(r.fields, "count", 4, count));
        if (info.chunk_pos < records_start_ || info.chunk_pos >= index_pos) {
          fail_record(r, "chunk_pos " + std::to_string(info.chunk_pos) +
                             " is outside the chunk section (" + std::to_string(records_start_) +
                             " to " + std::to_string(index_pos) + ")");
        }
        if (count * 8 != r.data_length) {
          fail_record(r, "the chunk info counts " + std::to_string(count) + " connections in " +
                             std::to_string(r.data_length) + " bytes (8 bytes each)");
        }
        file_.read(r.data_offset, r.data_length, data_buf_, "chunk info data");
        for (std::uint64_t i = 0; i < count; ++i) {
          info.counts.emplace_back(load_le32(data_buf_.data() + 8 * i),
                                   load_le32(data_buf_.data() + 8 * i + 4));
        }
        chunk_infos_.push_back(std::move(info));
      } else {
        fail_record(r, "unexpected record op " + op_text(r.op) + " in the index section");
      }
      pos = r.data_offset + r.data_length;
    }
    for (const ChunkInfo& info : chunk_infos_) {
      for (const auto& [id, count] : info.counts) {
        const auto c = find_connection(id);
        if (!c) {
          file_.fail(index_pos, "a chunk info counts messages of connection " + std::to_string(id) +
                                    ", which the index does not define");
        }
        connections_[*c].messages += count;
      }
    }
  }

  /// Decompresses the chunk R and walks its records.
  void chunk(const FileRecord& r, ChunkVisitor& visitor) {
    const Field* compression = find_field(r.fields, "compression");
    if (compression == nullptr) fail_record(r, "the chunk has no 'compression' field");
    std::uint64_t size = 0;
    check(r, integer_field(r.fields, "size", 4, size));
    const std::string_view name = text_of(compression->value);
    file_.read(r.data_offset, r.data_length, data_buf_, "chunk data");
    Bytes records = data_buf_;
    if (name == "none") {
      if (size != r.data_length) {
        fail_record(r, "uncompressed chunk of " + std::to_string(r.data_length) +
                           " bytes declares size " + std::to_string(size));
      }
    } else {
      ChunkCompression kind = ChunkCompression::kNone;
      if (name == "bz2") {
        kind = ChunkCompression::kBz2;
      } else if (name == "lz4") {
        kind = ChunkCompression::kLz4;
      } else {
        fail_record(r, "unknown chunk compression " + quoted_bytes(name) +
                           " (a bag 2.0 chunk is none, bz2 or lz4)");
      }
      decompress_chunk(kind, data_buf_, size, chunk_buf_, file_.path(), r.offset);
      records = chunk_buf_;
    }
    chunk_records(r.offset, records, visitor);
  }

  void chunk_records(std::uint64_t chunk_offset, Bytes records, ChunkVisitor& visitor) {
    std::size_t pos = 0;
    const auto fail = [&](const std::string& problem) {
      file_.fail(chunk_offset,
                 "in the chunk's records at offset " + std::to_string(pos) + ": " + problem);
    };
    while (pos < records.size()) {
      if (records.size() - pos < 4) fail("truncated record header length");
      const std::uint32_t header_length = load_le32(records.data() + pos);
      if (header_length > records.size() - pos - 4 ||
          records.size() - pos - 4 - header_length < 4) {
        fail("a record header of " + std::to_string(header_length) +
             " bytes runs past the end of the chunk");
      }
      const Bytes header = records.subspan(pos + 4, header_length);
      const std::size_t data_at = pos + 8 + header_length;
      const std::uint32_t data_length = load_le32(records.data() + data_at - 4);
      if (data_length > records.size() - data_at) {
        fail("record data of " + std::to_string(data_length) +
             " bytes runs past the end of the chunk");
      }
      const Bytes data = records.subspan(data_at, data_length);
      if (const std::string e = parse_fields(header, fields_); !e.empty()) fail(e);
      std::uint64_t op = 0;
      if (const std::string e = integer_field(fields_, "op", 1, op); !e.empty()) fail(e);
      std::uint64_t id = 0;
      if (op == kOpMessageData || op == kOpConnection) {
        if (const std::string e = integer_field(fields_, "conn", 4, id); !e.empty()) fail(e);
      }
      if (op == kOpMessageData) {
        const Field* time = find_field(fields_, "time");
        if (time == nullptr || time->value.size() != 8) fail("a message record has no 8-byte time");
        const auto conn = find_connection(static_cast<std::uint32_t>(id));
        if (!conn) fail("a message of connection " + std::to_string(id) + " before its definition");
        visitor.message(*conn, time_ns(time->value), data, chunk_offset, pos);
      } else if (op == kOpConnection) {
        const Field* topic = find_field(fields_, "topic");
        if (topic == nullptr) fail("the connection record has no 'topic' field");
        connection(static_cast<std::uint32_t>(id), std::string(text_of(topic->value)), data,
                   chunk_offset, " (in the chunk's records at offset " + std::to_string(pos) + ")");
      } else {
        fail("unexpected record op " + op_text(static_cast<std::uint8_t>(op)) + " in a chunk");
      }
      pos = data_at + data_length;
    }
  }

  BinaryFile file_;
  std::uint64_t records_start_ = 0;
  bool indexed_ = false;
  std::vector<Connection> connections_;
  std::map<std::uint32_t, std::size_t> ids_;
  std::vector<ChunkInfo> chunk_infos_;
  std::vector<std::uint8_t> length_buf_, header_buf_, data_buf_, chunk_buf_;
  std::vector<Field> fields_, data_fields_;
};

/// Counts the messages of each connection (an unindexed bag's scan).
struct CountingVisitor : ChunkVisitor {
  explicit CountingVisitor(Bag& bag) : bag_(bag) {}
  void message(std::size_t conn, std::int64_t, Bytes, std::uint64_t, std::size_t) override {
    ++counts[conn];
  }
  Bag& bag_;
  std::map<std::size_t, std::int64_t> counts;
};

std::vector<LogTopic> topics_of(const std::vector<Connection>& connections,
                                const std::map<std::size_t, std::int64_t>* counts) {
  std::vector<LogTopic> topics;
  for (std::size_t i = 0; i < connections.size(); ++i) {
    const Connection& c = connections[i];
    auto it = std::find_if(topics.begin(), topics.end(),
                           [&](const LogTopic& t) { return t.name == c.topic; });
    if (it == topics.end()) {
      LogTopic t;
      t.name = c.topic;
      t.type = c.type;
      t.is_imu = c.type == kRos1ImuType;
      topics.push_back(std::move(t));
      it = topics.end() - 1;
    }
    if (counts == nullptr) {
      it->message_count += c.messages;
    } else if (const auto n = counts->find(i); n != counts->end()) {
      it->message_count += n->second;
    }
  }
  return topics;
}

/// Decodes the messages of the chosen topic's connections into a collector.
struct ImuVisitor : ChunkVisitor {
  ImuVisitor(Bag& bag, std::string topic, const LogReadOptions& options)
      : bag_(bag), topic_(std::move(topic)), samples(options, ros_imu_fields(), si_imu_units()) {}

  void message(std::size_t conn, std::int64_t log_time_ns, Bytes data, std::uint64_t chunk_offset,
               std::size_t offset_in_chunk) override {
    ++counts[conn];
    const Connection& c = bag_.connections()[conn];
    if (c.topic != topic_) return;
    const auto where = [&] {
      return "in the chunk's records at offset " + std::to_string(offset_in_chunk) + ": topic " +
             quoted_bytes(topic_) + ": ";
    };
    if (c.type != kRos1ImuType) {
      bag_file_fail(chunk_offset, where() + "a message of type " + quoted_bytes(c.type) +
                                      " (connection " + std::to_string(c.id) +
                                      "), not sensor_msgs/Imu");
    }
    if (!c.md5sum.empty() && c.md5sum != kRos1ImuMd5 && c.md5sum != "*") {
      bag_file_fail(chunk_offset, where() + "md5sum " + quoted_bytes(c.md5sum) +
                                      " differs from sensor_msgs/Imu's " +
                                      std::string(kRos1ImuMd5));
    }
    if (!decode_ros1_imu(data, message_, error_)) bag_file_fail(chunk_offset, where() + error_);
    if (const std::string* bad = samples.add(message_, log_time_ns)) {
      bag_file_fail(chunk_offset, where() + "non-finite value in " + *bad +
                                      " (give --drop-non-finite to drop such messages)");
    }
  }
  [[noreturn]] void bag_file_fail(std::uint64_t offset, const std::string& problem) const {
    throw_at_offset(bag_.path(), offset, problem);
  }
  const std::string& topic() const { return topic_; }

  Bag& bag_;
  std::string topic_;
  ImuSampleCollector samples;
  std::map<std::size_t, std::int64_t> counts;
  ImuMessage message_;
  std::string error_;
};

/// The scan of an unindexed bag: decodes the first sensor_msgs/Imu topic found (or the one
/// OPTIONS.topic names) and counts the messages of every connection.
struct FirstImuVisitor : ChunkVisitor {
  FirstImuVisitor(Bag& bag, const LogReadOptions& options) : bag_(bag), options_(options) {}
  void message(std::size_t conn, std::int64_t t, Bytes data, std::uint64_t chunk_offset,
               std::size_t offset_in_chunk) override {
    if (!inner) {
      const Connection& c = bag_.connections()[conn];
      if (c.type != kRos1ImuType || (!options_.topic.empty() && c.topic != options_.topic)) {
        ++early_counts[conn];
        return;
      }
      inner = std::make_unique<ImuVisitor>(bag_, c.topic, options_);
      inner->counts = std::move(early_counts);
    }
    inner->message(conn, t, data, chunk_offset, offset_in_chunk);
  }
  Bag& bag_;
  const LogReadOptions& options_;
  std::unique_ptr<ImuVisitor> inner;
  std::map<std::size_t, std::int64_t> early_counts;
};

}  // namespace

bool is_rosbag1_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kMagicBytes, '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) return false;
  return head == kRosbag1Magic;
}

std::vector<LogTopic> list_rosbag1_topics(const std::string& path) {
  Bag bag(path);
  if (bag.indexed()) return topics_of(bag.connections(), nullptr);
  CountingVisitor counter(bag);
  bag.walk({}, counter);
  return topics_of(bag.connections(), &counter.counts);
}

pipeline::Recording read_rosbag1_imu(const std::string& path, const LogReadOptions& options) {
  Bag bag(path);
  if (bag.indexed()) {
    const std::vector<LogTopic> topics = topics_of(bag.connections(), nullptr);
    const LogTopic& topic = select_imu_topic(path, topics, options, kFileKind);
    std::vector<std::uint32_t> ids;
    for (const Connection& c : bag.connections()) {
      if (c.topic == topic.name) ids.push_back(c.id);
    }
    std::vector<std::uint64_t> positions;
    for (const ChunkInfo& info : bag.chunk_infos()) {
      const bool has_topic =
          std::any_of(info.counts.begin(), info.counts.end(), [&](const auto& p) {
            return p.second > 0 && std::find(ids.begin(), ids.end(), p.first) != ids.end();
          });
      if (has_topic) positions.push_back(info.chunk_pos);
    }
    ImuVisitor visitor(bag, topic.name, options);
    visitor.samples.reserve(topic.message_count, bag.file_size());
    bag.walk(positions, visitor);
    return visitor.samples.finish(path, topic.name);
  }
  // No index: the topics are known only once every chunk has been read, so one scan decodes
  // the first sensor_msgs/Imu topic (or the named one) and counts the rest; the choice is then
  // checked against the full listing.
  FirstImuVisitor first(bag, options);
  bag.walk({}, first);
  const std::map<std::size_t, std::int64_t>& counts =
      first.inner ? first.inner->counts : first.early_counts;
  const std::vector<LogTopic> topics = topics_of(bag.connections(), &counts);
  const LogTopic& topic = select_imu_topic(path, topics, options, kFileKind);
  if (!first.inner || first.inner->topic() != topic.name) {
    throw InputError(located_message(
        path, 0, 0, "no sensor_msgs/Imu message on topic " + quoted_bytes(topic.name)));
  }
  return first.inner->samples.finish(path, topic.name);
}

}  // namespace imunoise::io
