// Crash safety of a stateful node (backend, room_segmentation, loop_closure): every message the
// node takes is appended to a journal file as it arrives, and a node killed mid-run (kill -9, an
// out-of-memory kill, a crash) and respawned by roslaunch rebuilds its state by replaying the
// file through its own callbacks, then asks the others to resend what it missed while it was
// down (tacs_graphs/Resync, docs/DESIGN.md "Crash safety").
//
// File: the magic "TACSJRN1", then records {uint8 channel, uint32 size, uint32 FNV-1a of the
// bytes, bytes}, each written with one fwrite and flushed to the kernel, so a killed process
// leaves at most its last record cut short; replay stops there and says so. (Flushed, not
// fsync'ed: a power cut may lose the last second.)
#pragma once

#include <ros/ros.h>
#include <ros/serialization.h>

#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tacs {

struct JournalReplay {
  size_t records = 0;
  size_t bytes = 0;        // of the whole records
  size_t valid_bytes = 0;  // length of the file up to the end of the last whole record
  /// Empty, or why the replay stopped early (a record cut short by a kill, a bad checksum).
  std::string stopped;
};

class MessageJournal {
 public:
  /// Opens `path` for appending; `truncate` starts a new journal (a fresh run). Creates the
  /// folder. Throws std::runtime_error naming the path.
  MessageJournal(const std::string& path, bool truncate);

  const std::string& path() const { return path_; }

  /// Appends one record. Throws std::runtime_error when the write fails (disk full).
  void append(uint8_t channel, const std::vector<uint8_t>& bytes);

  template <class Message>
  void appendMessage(uint8_t channel, const Message& msg) {
    append(channel, serialize(msg));
  }

  /// Reads `path` and calls `handle` for each whole record in order. A missing file is an empty
  /// journal. Throws std::runtime_error when the file is not a journal.
  static JournalReplay replay(
      const std::string& path,
      const std::function<void(uint8_t channel, const std::vector<uint8_t>& bytes)>& handle);

  template <class Message>
  static std::vector<uint8_t> serialize(const Message& msg) {
    std::vector<uint8_t> bytes(ros::serialization::serializationLength(msg));
    ros::serialization::OStream stream(bytes.data(), static_cast<uint32_t>(bytes.size()));
    ros::serialization::serialize(stream, msg);
    return bytes;
  }

  template <class Message>
  static boost::shared_ptr<Message> deserialize(const std::vector<uint8_t>& bytes) {
    auto msg = boost::make_shared<Message>();
    ros::serialization::IStream stream(const_cast<uint8_t*>(bytes.data()),
                                       static_cast<uint32_t>(bytes.size()));
    ros::serialization::deserialize(stream, *msg);
    return msg;
  }

 private:
  std::string path_;
  std::unique_ptr<FILE, int (*)(FILE*)> file_;
};

/// The journal of one stateful node. Reads ~journal_dir (empty: off) and ~replay_journal
/// ("auto": replay when this process is a respawn within the same launch, i.e. the private
/// parameter ~journal_started left by the previous process is there - the launch files clear a
/// node's private parameters at each launch; "true"; "false"). The file is
/// <journal_dir>/<node>.journal, emptied on a fresh start. Never throws: a journal that cannot be
/// opened or written is logged once and the node runs on without one.
class NodeJournal {
 public:
  using Handler = std::function<void(uint8_t channel, const std::vector<uint8_t>& bytes)>;

  NodeJournal(ros::NodeHandle& pnh, const std::string& node);

  /// True when this start must replay the journal before taking new messages.
  bool mustReplay() const { return must_replay_; }
  bool replaying() const { return replaying_; }

  /// Appends a message the node took (not while replaying).
  template <class Message>
  void record(uint8_t channel, const Message& msg) {
    if (journal_ && !replaying_) append(channel, MessageJournal::serialize(msg));
  }

  /// Replays the journal through `handle` (messages recorded meanwhile are not appended again)
  /// and logs what it read. Returns the number of records.
  size_t replay(const Handler& handle);

 private:
  void append(uint8_t channel, const std::vector<uint8_t>& bytes);

  std::string node_;
  std::unique_ptr<MessageJournal> journal_;
  bool must_replay_ = false;
  bool replaying_ = false;
};

}  // namespace tacs
