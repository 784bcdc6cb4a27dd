#include "tacs_graphs/common/message_reason.h"

#include <gtest/gtest.h>

namespace tacs {
namespace {

TEST(MessageReason, MessagesThatDifferOnlyInTheirNumbersAreOneReason) {
  EXPECT_EQ(messageReason("ground around the robot tilts 12.3 deg: is the scan aligned?"),
            messageReason("ground around the robot tilts 4.0 deg: is the scan aligned?"));
  EXPECT_EQ(messageReason("stamp -0.5 s before the last (at 10.25 s)."),
            "stamp # s before the last (at # s).");
  EXPECT_NE(messageReason("keyframe cloud: no x field"),
            messageReason("keyframe cloud: no z field"));
  EXPECT_EQ(messageReason("see the log."), "see the log.");
  EXPECT_EQ(messageReason("OS0-128 scan"), "OS#-# scan");  // a hyphen is no minus sign
}

}  // namespace
}  // namespace tacs
