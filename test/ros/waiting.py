"""Waiting for what a rostest checks, never sampling once after a fixed sleep.

Every wait polls its condition until it holds or a deadline passes. The deadlines are sized for
a machine three times slower than the one the suite was written on, with both cores busy:
`SLOW` scales a time that is enough on a fast idle machine. A wait that holds early returns at
once, so generous deadlines cost nothing when all is well."""
import threading
import time

import rospy

SLOW = 3.0


def wait_for(condition, timeout_s, period_s=0.1):
    """The first truthy value of condition() within timeout_s seconds (wall clock), else that
    last value (falsy). Stops early when rospy shuts down."""
    deadline = time.time() + timeout_s
    while True:
        value = condition()
        if value or time.time() >= deadline or rospy.is_shutdown():
            return value
        time.sleep(period_s)


def require(condition, timeout_s, what, period_s=0.1):
    """wait_for, raising AssertionError that names `what` when the deadline passes."""
    value = wait_for(condition, timeout_s, period_s)
    if not value:
        raise AssertionError('timed out after %.0f s waiting for %s' % (timeout_s, what))
    return value


def wait_stable(count, timeout_s, quiet_s=1.0, period_s=0.1):
    """Waits until count() has not changed for quiet_s seconds (or timeout_s passes) and returns
    it: for "exactly N" checks, where extra messages could still be on their way."""
    deadline = time.time() + timeout_s
    last, since = count(), time.time()
    while time.time() < deadline and not rospy.is_shutdown():
        time.sleep(period_s)
        now = count()
        if now != last:
            last, since = now, time.time()
        elif time.time() - since >= quiet_s:
            break
    return last


class ByStamp:
    """The messages of one topic by header stamp, and the last one received."""

    def __init__(self, topic, msg_type, queue_size=50):
        self.lock = threading.Lock()
        self.by_stamp = {}
        self.last = None
        self.sub = rospy.Subscriber(topic, msg_type, self.callback, queue_size=queue_size)

    def callback(self, msg):
        with self.lock:
            self.by_stamp[msg.header.stamp] = msg
            self.last = msg

    def get(self, stamp):
        with self.lock:
            return self.by_stamp.get(stamp)

    def latest(self):
        with self.lock:
            return self.last

    def wait(self, stamp, timeout_s=10.0 * SLOW):
        """The message stamped `stamp`, or None once timeout_s has passed."""
        return wait_for(lambda: self.get(stamp), timeout_s, period_s=0.01)

    def require(self, stamp, timeout_s=10.0 * SLOW):
        msg = self.wait(stamp, timeout_s)
        if msg is None:
            raise AssertionError('no message on %s for stamp %s within %.0f s' % (self.sub.name, stamp, timeout_s))
        return msg
