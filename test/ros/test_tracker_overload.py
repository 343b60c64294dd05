#!/usr/bin/env python3
"""rostest: the Tracker on sigma-60 noise with colors.txt. Every frame is processed (a blobs
message for every camera_info stamp), none takes over 5 ms, every class keeps its blobs, the
log says "too many regions" once, and /diagnostics says it with the class and its count."""
import re
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import CameraInfo
from rle_vision.msg import BlobArray

CLASSES = ('red', 'yellow', 'blue', 'magenta')
WINDOW_S = 8.0
MAX_FRAME_MS = 5.0


class TrackerOverloadTest(unittest.TestCase):
    def test_noisy_frames_stay_bounded(self):
        lock = threading.Lock()
        frames, blobs, warnings, statuses = [], {}, [], []

        def on_blobs(msg):
            with lock:
                blobs[msg.header.stamp.to_nsec()] = msg

        def on_info(msg):
            with lock:
                frames.append(msg.header.stamp.to_nsec())

        def on_log(msg):
            if msg.level == Log.WARN and 'too many regions' in msg.msg:
                with lock:
                    warnings.append(msg.msg)

        def on_diagnostics(msg):
            with lock:
                statuses.extend(s for s in msg.status if 'tracker' in s.name)

        rospy.Subscriber('/rosout', Log, on_log, queue_size=100)
        rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics, queue_size=20)
        rospy.Subscriber('/camera/blobs', BlobArray, on_blobs, queue_size=100)
        deadline = time.time() + 30
        while time.time() < deadline and not blobs:
            time.sleep(0.05)
        self.assertTrue(blobs, 'no blobs within 30 s')
        rospy.Subscriber('/camera/camera_info', CameraInfo, on_info, queue_size=100)
        time.sleep(WINDOW_S)
        with lock:
            window = list(frames)
        time.sleep(1.0)  # the blobs of the window's last frames
        with lock:
            got = dict(blobs)
            logged = list(warnings)
            reports = list(statuses)

        self.assertGreater(len(window), 0.8 * 30 * WINDOW_S, 'the simulator published %d frames' % len(window))
        missing = [s for s in window if s not in got]
        self.assertEqual(missing, [], '%d of %d frames got no blobs' % (len(missing), len(window)))
        times = [got[s].processing_time_ms for s in window]
        self.assertLessEqual(max(times), MAX_FRAME_MS, 'slowest frame %.2f ms' % max(times))
        for s in window:
            names = {b.color for b in got[s].blobs}
            self.assertEqual(names, set(CLASSES), 'frame %d has blobs of %s only' % (s, sorted(names)))
            self.assertTrue(all(b.area >= 20 for b in got[s].blobs), 'a blob under min_track_area_px')

        self.assertEqual(len(logged), 1, 'the overload warning was logged %d times: %s' % (len(logged), logged))
        for name in CLASSES:
            self.assertRegex(logged[0], r'too many regions for class %s \(\d+ > max_regions_per_class 500\)' % name)
        warned = [s for s in reports if s.level == DiagnosticStatus.WARN and 'too many regions for class' in s.message]
        self.assertTrue(warned, 'no diagnostics WARN about too many regions in %d reports' % len(reports))
        counts = [int(n) for n in re.findall(r'too many regions for class red \((\d+) >', warned[-1].message)]
        self.assertTrue(counts and counts[0] > 500, warned[-1].message)
        values = {v.key: v.value for v in warned[-1].values}
        self.assertGreater(int(values['frames with too many regions for class red (total)']), 0)
        rospy.loginfo('tracker overload: %d frames, slowest %.2f ms, mean %.2f ms; %s', len(window), max(times),
                      sum(times) / len(times), warned[-1].message)


if __name__ == '__main__':
    rospy.init_node('test_tracker_overload')
    rostest.rosrun('rle_vision', 'test_tracker_overload', TrackerOverloadTest)
