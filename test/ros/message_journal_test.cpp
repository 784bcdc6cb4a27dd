#include "tacs_graphs/ros/message_journal.h"

#include <gtest/gtest.h>
#include <tacs_graphs/LoopClosure.h>

#include <filesystem>
#include <fstream>

namespace tacs {
namespace {

std::string journalPath(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "tacs_message_journal_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

tacs_graphs::LoopClosure loop(uint32_t from, uint32_t to) {
  tacs_graphs::LoopClosure msg;
  msg.from_id = from;
  msg.to_id = to;
  msg.score = 0.5 + 0.01 * to;
  msg.information[7] = 42.0;
  return msg;
}

std::vector<tacs_graphs::LoopClosure> replayLoops(const std::string& path, JournalReplay* result) {
  std::vector<tacs_graphs::LoopClosure> loops;
  *result = MessageJournal::replay(path, [&](uint8_t channel, const std::vector<uint8_t>& bytes) {
    EXPECT_EQ(channel, 3);
    loops.push_back(*MessageJournal::deserialize<tacs_graphs::LoopClosure>(bytes));
  });
  return loops;
}

TEST(MessageJournal, MessagesComeBackInOrder) {
  const std::string path = journalPath("order.journal");
  {
    MessageJournal journal(path, /*truncate=*/true);
    for (uint32_t i = 0; i < 3; ++i) journal.appendMessage(3, loop(i, i + 1));
  }
  {
    MessageJournal again(path, /*truncate=*/false);  // a respawn appends
    again.appendMessage(3, loop(7, 8));
  }
  JournalReplay result;
  const auto loops = replayLoops(path, &result);
  ASSERT_EQ(loops.size(), 4u);
  EXPECT_EQ(loops[3].from_id, 7u);
  EXPECT_DOUBLE_EQ(loops[2].score, 0.53);
  EXPECT_DOUBLE_EQ(loops[1].information[7], 42.0);
  EXPECT_TRUE(result.stopped.empty());
  EXPECT_EQ(result.valid_bytes, std::filesystem::file_size(path));
  // A fresh run starts the journal empty.
  MessageJournal fresh(path, /*truncate=*/true);
  EXPECT_TRUE(replayLoops(path, &result).empty());
}

TEST(MessageJournal, ARecordCutShortByAKillEndsTheReplayThere) {
  const std::string path = journalPath("cut.journal");
  {
    MessageJournal journal(path, true);
    journal.appendMessage(3, loop(0, 1));
    journal.appendMessage(3, loop(1, 2));
  }
  const auto whole = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, whole - 5);
  JournalReplay result;
  EXPECT_EQ(replayLoops(path, &result).size(), 1u);
  EXPECT_NE(result.stopped.find("cut short"), std::string::npos) << result.stopped;
  EXPECT_LT(result.valid_bytes, whole - 5);

  // A flipped byte in a record is caught by its checksum.
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(20);
    f.put('\x7f');
  }
  EXPECT_TRUE(replayLoops(path, &result).empty());
  EXPECT_NE(result.stopped.find("checksum"), std::string::npos) << result.stopped;
}

TEST(MessageJournal, AMissingFileIsEmptyAndAForeignFileIsAnError) {
  JournalReplay result;
  EXPECT_TRUE(replayLoops(journalPath("never_written.journal"), &result).empty());
  const std::string foreign = journalPath("foreign.journal");
  std::ofstream(foreign) << "{\"not\": \"a journal\"}";
  EXPECT_THROW(replayLoops(foreign, &result), std::runtime_error);
  EXPECT_THROW(MessageJournal("/proc/no_such_dir/x.journal", true), std::runtime_error);
}

}  // namespace
}  // namespace tacs
