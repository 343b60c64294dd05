#!/usr/bin/env python3
"""rostest: faults. The pipeline runs with every nodelet in its own process (respawned by
roslaunch) on the drifting-light scene with colour learning on. Killing the Landmark process
(SIGKILL) does not disturb the tracker, which keeps the last learned ranges; the restarted
Landmark resumes from them; killing the tracker, the restarted one picks up the latched
learned ranges."""
import os
import signal
import sys
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
import yaml
from rle_vision.msg import BlobArray, ColorRangeArray, LineArray, SceneTruth

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from waiting import SLOW, require  # noqa: E402

PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def ranges_of(msg):
    return {(r.name, r.space): (tuple(r.min), tuple(r.max), r.source) for r in msg.ranges}


def pid_of(node):
    """The process id of a running node, or None while it is not (yet) reachable."""
    try:
        api = rosgraph.Master('/test_fault_recovery').lookupNode(node)
        return xmlrpc.client.ServerProxy(api).getPid('/test_fault_recovery')[2]
    except Exception:  # noqa: BLE001 (not registered, or the registered process is gone)
        return None


class Recorder:
    """Messages of one topic with their wall-clock arrival times."""

    def __init__(self, topic, msg_type):
        self.lock = threading.Lock()
        self.items = []
        rospy.Subscriber(topic, msg_type, self.callback, queue_size=200)

    def callback(self, msg):
        with self.lock:
            self.items.append((time.time(), msg))

    def since(self, t):
        with self.lock:
            return [m for (at, m) in self.items if at >= t]

    def last(self):
        with self.lock:
            return self.items[-1][1] if self.items else None

    def first_arrival_since(self, t):
        """The wall-clock arrival of the first message at or after t (None before one)."""
        with self.lock:
            return next((at for (at, _) in self.items if at >= t), None)


class FaultRecoveryTest(unittest.TestCase):
    def setUp(self):
        self.truth = Recorder('/camera/ground_truth/scene', SceneTruth)
        self.blobs = Recorder('/camera/blobs', BlobArray)
        self.lines = Recorder('/camera/lines', LineArray)
        self.learned = Recorder('/camera/color_ranges', ColorRangeArray)
        self.active = Recorder('/camera/tracker/active_color_ranges', ColorRangeArray)
        with open(os.path.join(PACKAGE_DIR, 'config', 'colors.yaml')) as f:
            self.configured = {(c['name'], c.get('space', 'YUV')): (tuple(c['min']), tuple(c['max']))
                               for c in yaml.safe_load(f)['classes']}

    def blob_share(self, start, end):
        """Share of the simulator frames stamped in [start, end) (wall time) that got blobs."""
        frames = [m.header.stamp for m in self.truth.since(start) if m.header.stamp.to_sec() < end]
        done = {m.header.stamp for m in self.blobs.since(start)}
        self.assertGreaterEqual(len(frames), 20)  # the outage lasts at least 1 s (30 frames); jitter takes a few
        return sum(1 for s in frames if s in done) / float(len(frames))

    def test_kill_and_restart_landmark_then_tracker(self):
        # 1. The loop runs: learned ranges reach the tracker.
        def learned_in_use():
            learned, active = self.learned.last(), self.active.last()
            if learned is None or active is None:
                return None
            l, a = ranges_of(learned), ranges_of(active)
            if any(v[2] == 'learned' for v in l.values()) and l == a:
                return learned
            return None
        require(learned_in_use, 90 * SLOW, 'learned colour ranges in use by the tracker')
        tracker_pid = pid_of('/camera/tracker')
        landmark_pid = pid_of('/camera/landmark')
        self.assertIsNotNone(tracker_pid)
        self.assertIsNotNone(landmark_pid)

        # 2. Kill the landmark; it comes back (roslaunch respawns it) and finds lines again.
        last_learned = ranges_of(self.learned.last())
        t_kill = time.time()
        os.kill(landmark_pid, signal.SIGKILL)
        require(lambda: pid_of('/camera/landmark') not in (None, landmark_pid), 30 * SLOW, 'the landmark to restart')
        require(lambda: self.lines.since(time.time() - 0.5) and self.lines.since(t_kill + 1.0), 30 * SLOW,
                'lines from the restarted landmark')
        t_back = time.time()
        # The tracker was not disturbed: same process, blobs for the frames, the learned ranges.
        self.assertEqual(pid_of('/camera/tracker'), tracker_pid)
        share = self.blob_share(t_kill, t_back)
        print('landmark down for %.1f s: tracker answered %.1f%% of the frames' % (t_back - t_kill, 100 * share))
        self.assertGreaterEqual(share, 0.9)
        active_during_outage = [m for m in self.active.since(t_kill)]
        for msg in active_during_outage:  # only ever learned ranges, never the configured ones again
            self.assertTrue(any(v[2] == 'learned' for v in ranges_of(msg).values()))
        # The restarted landmark resumed: its first ranges continue the learned ones.
        first = require(lambda: self.learned.since(t_kill), 30 * SLOW, 'colour ranges from the restarted landmark')[0]
        resumed = ranges_of(first)
        for key, (lo, hi, source) in last_learned.items():
            if source != 'learned' or key not in self.configured:
                continue
            new_lo, new_hi, new_source = resumed[key]
            self.assertEqual(new_source, 'learned', key)
            distance_to_last = sum(abs(a - b) for a, b in zip(new_lo + new_hi, lo + hi))
            distance_to_config = sum(abs(a - b) for a, b in zip(new_lo + new_hi, sum(self.configured[key], ())))
            self.assertLessEqual(distance_to_last, distance_to_config,
                                 '%s restarted from the configured range, not the learned one' % (key,))

        # 3. Kill the tracker: the restarted one takes the latched learned ranges.
        t_kill = time.time()
        os.kill(tracker_pid, signal.SIGKILL)
        require(lambda: pid_of('/camera/tracker') not in (None, tracker_pid), 30 * SLOW, 'the tracker to restart')

        def latched_ranges_in_use():
            latest = self.learned.last()
            for msg in self.active.since(t_kill):
                if ranges_of(msg) == ranges_of(latest):
                    return True
            return False
        require(latched_ranges_in_use, 30 * SLOW, 'the restarted tracker to use the latched learned ranges')
        # The window opens once the restarted tracker answers (it subscribes to the images apart
        # from taking the ranges above) and lasts 5 s. Counted from now, when the new process
        # is up: a blob of the killed one may still arrive just after the kill.
        t_restarted = time.time()
        t_answering = require(lambda: self.blobs.first_arrival_since(t_restarted), 30 * SLOW,
                              'blobs from the restarted tracker')
        require(lambda: self.blobs.since(t_answering + 5.5), 30 * SLOW, 'blobs 5 s after the restarted tracker answered')
        share = self.blob_share(t_answering + 0.5, time.time() - 0.5)
        print('restarted tracker answered %.1f%% of the frames' % (100 * share))
        self.assertGreaterEqual(share, 0.9)


if __name__ == '__main__':
    rospy.init_node('test_fault_recovery')
    rostest.rosrun('rle_vision', 'test_fault_recovery', FaultRecoveryTest)
