#include "aesim/event_files/rosbag2_sqlite.hpp"

#include <sqlite3.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string_view>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/ros_event_messages.hpp"

namespace aesim {
namespace {

constexpr std::string_view kSqliteMagic("SQLite format 3\0", 16);

struct SqliteTopic {
  std::string name;
  RosEventLayout layout = RosEventLayout::Other;
};

class SqliteBag {
 public:
  SqliteBag(const std::string& data, const std::string& label) : label_(label) {
    if (data.compare(0, kSqliteMagic.size(), kSqliteMagic) != 0) {
      throw InputError(fmt::format("event file '{}': not an SQLite database (a ROS 2 .db3 bag is one)", label_));
    }
    sqlite3* raw = nullptr;
    const int opened = sqlite3_open_v2(":memory:", &raw, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
    db_.reset(raw);
    if (opened != SQLITE_OK) throw std::bad_alloc();
    // A bag recorded in write-ahead-log mode says so in its header's two version bytes; SQLite's
    // in-memory databases keep no log, and a closed bag's log is already in the file, so a copy
    // saying "rollback journal" instead is given to SQLite. Otherwise SQLite reads the bytes as
    // they are: read-only, it does not write to them.
    const std::string* bytes = &data;
    if (data.size() >= 20 && data[18] == 2 && data[19] == 2) {
      patched_ = data;
      patched_[18] = patched_[19] = 1;
      bytes = &patched_;
    }
    const int loaded = sqlite3_deserialize(db_.get(), "main", reinterpret_cast<unsigned char*>(const_cast<char*>(bytes->data())),
                                           static_cast<sqlite3_int64>(bytes->size()), static_cast<sqlite3_int64>(bytes->size()),
                                           SQLITE_DESERIALIZE_READONLY);
    if (loaded != SQLITE_OK) fail("SQLite could not open it");
  }

  void read(RosEventTopics& topics) {
    if (!has_table("topics") || !has_table("messages")) {
      throw InputError(fmt::format("event file '{}': an SQLite database without rosbag2's topics and messages tables", label_));
    }
    // The .msg text of each type, where the bag keeps it (rosbag2 since Iron).
    std::map<std::string, std::string> definitions;
    if (has_table("message_definitions")) {
      query("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions", [&](sqlite3_stmt* s) {
        if (text(s, 1) == "ros2msg") definitions[std::string(text(s, 0))] = std::string(text(s, 2));
      });
    }
    std::map<std::int64_t, SqliteTopic> by_id;
    query("SELECT id, name, type, serialization_format FROM topics ORDER BY id", [&](sqlite3_stmt* s) {
      SqliteTopic t;
      t.name = std::string(text(s, 1));
      const std::string type(text(s, 2));
      const auto definition = definitions.find(type);
      t.layout = text(s, 3) == "cdr" ? ros_event_layout(type, definition == definitions.end() ? "" : definition->second)
                                     : RosEventLayout::Other;
      topics.declare(t.name, type);
      by_id[sqlite3_column_int64(s, 0)] = t;
    });
    query("SELECT topic_id, data FROM messages ORDER BY id", [&](sqlite3_stmt* s) {
      const auto it = by_id.find(sqlite3_column_int64(s, 0));
      if (it == by_id.end()) {
        throw InputError(fmt::format("event file '{}': a message of topic {}, which the topics table does not hold", label_,
                                     sqlite3_column_int64(s, 0)));
      }
      const auto* blob = static_cast<const char*>(sqlite3_column_blob(s, 1));
      topics.message(it->second.name, it->second.layout, RosWire::Cdr,
                     std::string_view(blob == nullptr ? "" : blob, static_cast<std::size_t>(sqlite3_column_bytes(s, 1))));
    });
  }

 private:
  [[noreturn]] void fail(const char* doing) const {
    throw InputError(fmt::format("event file '{}': {}: {}", label_, doing, sqlite3_errmsg(db_.get())));
  }

  bool has_table(const char* name) {
    bool found = false;
    query(fmt::format("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = '{}'", name), [&](sqlite3_stmt*) { found = true; });
    return found;
  }

  static std::string_view text(sqlite3_stmt* s, int column) {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(s, column));
    return p == nullptr ? std::string_view() : std::string_view(p, static_cast<std::size_t>(sqlite3_column_bytes(s, column)));
  }

  // Runs `sql`, calling `row` on each row; a malformed database is an InputError.
  template <typename Row>
  void query(const std::string& sql, Row row) {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) fail("SQLite could not read its tables");
    const std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)> statement(raw, sqlite3_finalize);
    for (;;) {
      const int step = sqlite3_step(statement.get());
      if (step == SQLITE_DONE) return;
      if (step != SQLITE_ROW) fail("SQLite could not read its tables");
      row(statement.get());
    }
  }

  std::string label_;
  std::string patched_;  // a write-ahead-log bag's bytes as SQLite reads them; outlives db_
  std::unique_ptr<sqlite3, decltype(&sqlite3_close)> db_{nullptr, sqlite3_close};
};

}  // namespace

void read_rosbag2_sqlite_topics(const std::string& data, const std::string& label, RosEventTopics& topics) {
  SqliteBag(data, label).read(topics);
}

PolarityRecording decode_rosbag2_sqlite(const std::string& data, const std::string& label) {
  RosEventTopics topics(label);
  read_rosbag2_sqlite_topics(data, label, topics);
  return topics.result();
}

}  // namespace aesim
