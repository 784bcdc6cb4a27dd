#include "tacs_graphs/ros/message_journal.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tacs_graphs/common/file_io.h"

namespace tacs {
namespace {

constexpr char kMagic[] = "TACSJRN1";
constexpr size_t kMagicSize = 8;
constexpr size_t kHeaderSize = 1 + 4 + 4;  // channel, size, checksum

uint32_t fnv1a(const std::vector<uint8_t>& bytes) {
  uint32_t h = 2166136261u;
  for (uint8_t b : bytes) h = (h ^ b) * 16777619u;
  return h;
}

void putU32(uint8_t* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<uint8_t>(v >> (8 * i));
}

uint32_t getU32(const uint8_t* in) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(in[i]) << (8 * i);
  return v;
}

std::string folderOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

MessageJournal::MessageJournal(const std::string& path, bool truncate)
    : path_(path), file_(nullptr, &std::fclose) {
  ensureDirectory(folderOf(path));
  bool fresh = truncate;
  if (!truncate) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    fresh = !in || in.tellg() == 0;
  }
  file_.reset(std::fopen(path.c_str(), fresh ? "wb" : "ab"));
  if (!file_) throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
  if (fresh && (std::fwrite(kMagic, 1, kMagicSize, file_.get()) != kMagicSize ||
                std::fflush(file_.get()) != 0)) {
    throw std::runtime_error(path + ": cannot write: " + std::strerror(errno));
  }
}

void MessageJournal::append(uint8_t channel, const std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> record(kHeaderSize + bytes.size());
  record[0] = channel;
  putU32(&record[1], static_cast<uint32_t>(bytes.size()));
  putU32(&record[5], fnv1a(bytes));
  std::memcpy(record.data() + kHeaderSize, bytes.data(), bytes.size());
  if (std::fwrite(record.data(), 1, record.size(), file_.get()) != record.size() ||
      std::fflush(file_.get()) != 0) {
    throw std::runtime_error(path_ + ": cannot append: " + std::strerror(errno));
  }
}

JournalReplay MessageJournal::replay(
    const std::string& path,
    const std::function<void(uint8_t channel, const std::vector<uint8_t>& bytes)>& handle) {
  JournalReplay result;
  std::ifstream in(path, std::ios::binary);
  if (!in) return result;
  char magic[kMagicSize] = {};
  in.read(magic, kMagicSize);
  if (in.gcount() == 0) return result;
  if (in.gcount() != static_cast<std::streamsize>(kMagicSize) ||
      std::memcmp(magic, kMagic, kMagicSize) != 0) {
    throw std::runtime_error(path + ": not a tacs_graphs journal");
  }
  result.valid_bytes = kMagicSize;
  std::vector<uint8_t> bytes;
  while (true) {
    uint8_t header[kHeaderSize];
    in.read(reinterpret_cast<char*>(header), kHeaderSize);
    if (in.gcount() == 0) break;
    const std::string where = "record " + std::to_string(result.records + 1);
    if (in.gcount() != static_cast<std::streamsize>(kHeaderSize)) {
      result.stopped = where + " cut short (the process was killed while writing it)";
      break;
    }
    bytes.resize(getU32(&header[1]));
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (in.gcount() != static_cast<std::streamsize>(bytes.size())) {
      result.stopped = where + " cut short (the process was killed while writing it)";
      break;
    }
    if (fnv1a(bytes) != getU32(&header[5])) {
      result.stopped = where + " has a bad checksum";
      break;
    }
    handle(header[0], bytes);
    ++result.records;
    result.bytes += kHeaderSize + bytes.size();
    result.valid_bytes += kHeaderSize + bytes.size();
  }
  return result;
}

NodeJournal::NodeJournal(ros::NodeHandle& pnh, const std::string& node) : node_(node) {
  const std::string dir = pnh.param<std::string>("journal_dir", "");
  if (dir.empty()) return;
  std::string mode = pnh.param<std::string>("replay_journal", "auto");
  if (mode != "auto" && mode != "true" && mode != "false") {
    ROS_WARN_STREAM(node << ": ~replay_journal is '" << mode
                         << "', expected auto, true or false; auto used");
    mode = "auto";
  }
  const bool respawned = pnh.hasParam("journal_started");
  must_replay_ = mode == "true" || (mode == "auto" && respawned);
  try {
    journal_ = std::make_unique<MessageJournal>(dir + "/" + node + ".journal", !must_replay_);
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM(node << ": no crash journal, a restart would start empty: " << e.what());
    must_replay_ = false;
    return;
  }
  pnh.setParam("journal_started", ros::WallTime::now().toSec());
  if (respawned && !must_replay_) {
    ROS_WARN_STREAM(node << ": restarted with ~replay_journal false: starting empty");
  }
}

size_t NodeJournal::replay(const Handler& handle) {
  if (!journal_) return 0;
  const std::string path = journal_->path();
  replaying_ = true;
  JournalReplay result;
  try {
    result = MessageJournal::replay(path, handle);
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM(node_ << ": journal not replayed: " << e.what());
  }
  replaying_ = false;
  if (!result.stopped.empty() && result.valid_bytes > 0) {
    // New records go after the last whole one (the file is appended to with O_APPEND).
    std::error_code error;
    std::filesystem::resize_file(path, result.valid_bytes, error);
    if (error) {
      ROS_ERROR_STREAM(node_ << ": cannot cut the broken tail of " << path << ": "
                             << error.message() << "; journaling stops");
      journal_.reset();
    }
  }
  ROS_WARN_STREAM(node_ << ": restarted; replayed " << result.records << " messages ("
                        << result.bytes / 1024 << " KiB) from " << path
                        << (result.stopped.empty() ? "" : "; stopped early: " + result.stopped));
  return result.records;
}

void NodeJournal::append(uint8_t channel, const std::vector<uint8_t>& bytes) {
  try {
    journal_->append(channel, bytes);
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM(node_ << ": " << e.what() << "; journaling stops, a restart would lose "
                           << "what follows");
    journal_.reset();
  }
}

}  // namespace tacs
