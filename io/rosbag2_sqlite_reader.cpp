/// @file
/// @brief rosbag2 sqlite3 reader (see rosbag2_sqlite_reader.h).
#include "io/rosbag2_sqlite_reader.h"

#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <span>
#include <utility>

#include "common/errors.h"
#include "io/binary_file.h"
#include "io/ros_imu_message.h"

namespace imunoise::io {
namespace {

constexpr std::string_view kFileKind = "rosbag2 database";

/// A read-only connection; every failure an InputError naming the file.
class Database {
 public:
  explicit Database(std::string path) : path_(std::move(path)) {
    if (!is_sqlite_file(path_)) {
      std::ifstream in(path_);
      fail(in ? "not a rosbag2 .db3 file (no \"SQLite format 3\" header)" : "cannot open");
    }
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(path_.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) fail(std::string("cannot open: ") + message());
    for (const char* table : {"topics", "messages"}) {
      Statement s(*this, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?1");
      sqlite3_bind_text(s.get(), 1, table, -1, SQLITE_STATIC);
      if (!s.step()) {
        fail(std::string("an SQLite database without the table '") + table +
             "' is not a rosbag2 bag");
      }
    }
  }

  const std::string& path() const { return path_; }
  sqlite3* get() const { return db_.get(); }
  std::string message() const { return db_ ? sqlite3_errmsg(db_.get()) : "out of memory"; }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(located_message(path_, 0, 0, problem));
  }

  /// One prepared statement.
  class Statement {
   public:
    Statement(const Database& db, const char* sql) : db_(db) {
      sqlite3_stmt* s = nullptr;
      if (sqlite3_prepare_v2(db.get(), sql, -1, &s, nullptr) != SQLITE_OK) {
        db.fail("SQLite: " + db.message() + " (in \"" + sql + "\")");
      }
      stmt_.reset(s);
    }
    sqlite3_stmt* get() const { return stmt_.get(); }
    /// True for a row, false at the end; an InputError for a failure (a corrupt database).
    bool step() {
      const int rc = sqlite3_step(stmt_.get());
      if (rc == SQLITE_ROW) return true;
      if (rc == SQLITE_DONE) return false;
      db_.fail("SQLite: " + db_.message());
    }
    std::string text(int column) const {
      const auto* p = sqlite3_column_text(stmt_.get(), column);
      return p == nullptr
                 ? std::string()
                 : std::string(reinterpret_cast<const char*>(p),
                               static_cast<std::size_t>(sqlite3_column_bytes(stmt_.get(), column)));
    }
    std::int64_t integer(int column) const { return sqlite3_column_int64(stmt_.get(), column); }
    std::span<const std::uint8_t> blob(int column) const {
      const void* p = sqlite3_column_blob(stmt_.get(), column);
      const int n = sqlite3_column_bytes(stmt_.get(), column);
      if (p == nullptr || n <= 0) return {};
      return {static_cast<const std::uint8_t*>(p), static_cast<std::size_t>(n)};
    }

   private:
    struct Finalize {
      void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
    };
    const Database& db_;
    std::unique_ptr<sqlite3_stmt, Finalize> stmt_;
  };

 private:
  struct Close {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
  };
  std::string path_;
  std::unique_ptr<sqlite3, Close> db_;
};

struct Topic {
  std::int64_t id = 0;
  LogTopic listing;
};

std::vector<Topic> read_topics(const Database& db) {
  std::vector<Topic> topics;
  Database::Statement t(db, "SELECT id, name, type, serialization_format FROM topics ORDER BY id");
  while (t.step()) {
    Topic topic;
    topic.id = t.integer(0);
    topic.listing.name = t.text(1);
    topic.listing.type = t.text(2);
    topic.listing.is_imu = topic.listing.type == kRos2ImuType && t.text(3) == "cdr";
    topics.push_back(std::move(topic));
  }
  std::map<std::int64_t, std::int64_t> counts;
  Database::Statement c(db, "SELECT topic_id, COUNT(*) FROM messages GROUP BY topic_id");
  while (c.step()) counts[c.integer(0)] = c.integer(1);
  for (Topic& topic : topics) {
    if (const auto it = counts.find(topic.id); it != counts.end()) {
      topic.listing.message_count = it->second;
    }
  }
  return topics;
}

std::vector<LogTopic> listing_of(const std::vector<Topic>& topics) {
  std::vector<LogTopic> out;
  for (const Topic& t : topics) out.push_back(t.listing);
  return out;
}

}  // namespace

bool is_sqlite_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kSqliteMagic.size(), '\0');
  if (!in.read(head.data(), static_cast<std::streamsize>(head.size()))) return false;
  return head == kSqliteMagic;
}

std::vector<LogTopic> list_rosbag2_sqlite_topics(const std::string& path) {
  const Database db(path);
  return listing_of(read_topics(db));
}

pipeline::Recording read_rosbag2_sqlite_imu(const std::string& path,
                                            const LogReadOptions& options) {
  const Database db(path);
  const std::vector<Topic> topics = read_topics(db);
  const std::vector<LogTopic> listing = listing_of(topics);
  const LogTopic& chosen = select_imu_topic(path, listing, options, kFileKind);
  ImuSampleCollector samples(options, ros_imu_fields(), si_imu_units());
  // COUNT(*) of the rows themselves; the file size bounds it all the same.
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  samples.reserve(chosen.message_count, ec ? 0 : bytes);
  ImuMessage message;
  std::string error;
  for (const Topic& topic : topics) {
    if (topic.listing.name != chosen.name) continue;
    Database::Statement m(db,
                          "SELECT id, timestamp, data FROM messages WHERE topic_id = ?1 "
                          "ORDER BY id");
    sqlite3_bind_int64(m.get(), 1, topic.id);
    while (m.step()) {
      const auto where = [&] {
        return "row id " + std::to_string(m.integer(0)) + " of table messages (topic " +
               quoted_bytes(chosen.name) + "): ";
      };
      if (!decode_cdr_imu(m.blob(2), message, error)) db.fail(where() + error);
      if (const std::string* bad = samples.add(message, m.integer(1))) {
        db.fail(where() + "non-finite value in " + *bad +
                " (give --drop-non-finite to drop such messages)");
      }
    }
  }
  return samples.finish(path, chosen.name);
}

}  // namespace imunoise::io
