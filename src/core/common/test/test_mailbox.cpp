// The landmark node's one-slot mailbox: the consumer sees only ever newer items, nothing is
// lost without being counted as dropped, close() wakes a waiting consumer. Also built under
// ThreadSanitizer (test_concurrency_tsan). Also the wait watchdog that says when inputs are stuck.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "rle_vision/common/latest_mailbox.h"
#include "rle_vision/common/startup_wait.h"
#include "rle_vision/common/wait_watchdog.h"

namespace rle_vision {
namespace {

TEST(LatestMailbox, ConsumerSeesNewerItemsAndEveryItemIsTakenOrDropped) {
  LatestMailbox<int> mailbox;
  constexpr int kItems = 20000;
  std::atomic<int> taken{0};
  int last = -1;
  bool increasing = true;
  std::thread consumer([&] {
    int item = 0;
    while (mailbox.take(&item)) {
      increasing = increasing && item > last;
      last = item;
      ++taken;
      if (item % 7 == 0) std::this_thread::yield();  // a slow consumer now and then
    }
  });
  int dropped = 0;
  for (int i = 0; i < kItems; ++i) dropped += mailbox.put(i);
  while (!mailbox.empty()) std::this_thread::yield();
  mailbox.close();
  consumer.join();
  EXPECT_TRUE(increasing);
  EXPECT_EQ(last, kItems - 1);  // the newest item is never lost
  EXPECT_EQ(taken + dropped, kItems);
  EXPECT_GT(taken, 0);
}

TEST(LatestMailbox, CloseWakesAWaitingConsumer) {
  LatestMailbox<int> mailbox;
  std::atomic<bool> returned{false};
  std::thread consumer([&] {
    int item = 0;
    EXPECT_FALSE(mailbox.take(&item));
    returned = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(returned);
  mailbox.close();
  consumer.join();
  EXPECT_TRUE(returned);
  EXPECT_FALSE(mailbox.put(1));  // puts after close are harmless
}

}  // namespace
}  // namespace rle_vision

namespace rle_vision {
namespace {

// The landmark node's start-up wait for camera_info: from the first call, for its duration.
TEST(StartupWait, WaitsFromTheFirstCallForItsDuration) {
  StartupWait wait(1.0);
  EXPECT_DOUBLE_EQ(wait.remaining(50.0), 1.0);  // not started yet
  EXPECT_TRUE(wait.waiting(100.0));
  EXPECT_DOUBLE_EQ(wait.remaining(100.25), 0.75);
  EXPECT_TRUE(wait.waiting(100.9));
  EXPECT_FALSE(wait.waiting(101.0));
  EXPECT_DOUBLE_EQ(wait.remaining(102.0), 0.0);
}

}  // namespace
}  // namespace rle_vision

namespace rle_vision {
namespace {

TEST(WaitWatchdog, OverdueFromTheOldestUnhandledInputUntilOneIsHandled) {
  WaitWatchdog watchdog(1.0);
  EXPECT_EQ(watchdog.overdueS(5.0), 0.0);  // nothing waits
  watchdog.received(10.0);
  watchdog.received(10.5);  // a later input does not restart the wait
  EXPECT_EQ(watchdog.overdueS(10.9), 0.0);
  EXPECT_DOUBLE_EQ(watchdog.overdueS(11.0), 1.0);
  EXPECT_DOUBLE_EQ(watchdog.overdueS(12.5), 2.5);
  watchdog.handled();
  EXPECT_EQ(watchdog.overdueS(13.0), 0.0);
  watchdog.received(13.0);
  EXPECT_EQ(watchdog.overdueS(13.5), 0.0);
  EXPECT_DOUBLE_EQ(watchdog.overdueS(14.25), 1.25);
}

}  // namespace
}  // namespace rle_vision
