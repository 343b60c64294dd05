#!/usr/bin/env python3
"""rostest: every nodelet of the demo graph reports on /diagnostics: input rate, processing
time (mean, max), frames dropped, and the age of the colour ranges (tracker and landmark).
The test listens until every node has sent enough reports and learning has reached the
tracker (on a slow machine the first reports come late), then checks the reports: the nodes
on the camera's path take every frame the simulator sends, and the landmark, at low priority,
takes frames too."""
import sys
import threading
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from waiting import SLOW, wait_for  # noqa: E402

SIMULATOR = 'camera/simulator: simulator'
TRACKER = 'camera/tracker: tracker'
LANDMARK = 'camera/landmark: landmark'
EXPECTED = {  # status name -> (lowest input rate as a share of the simulator's, extra keys)
    SIMULATOR: (1.0, ['frames published']),
    TRACKER: (0.8, ['colour classes', 'colour ranges from', 'colour ranges age (s)']),
    'camera/edge_detector: edge detector': (0.8, []),
    LANDMARK: (0.1, ['colour learning', 'learned colour classes', 'colour ranges age (s)']),
    'camera/ground_projector: ground projector': (0.8, []),
}
COMMON = ['input rate (Hz)', 'processing time mean (ms)', 'processing time max (ms)',
          'frames dropped (since last report)', 'frames dropped (total)']
REPORTS = 5  # 1-s reports per node, for a median rate


def median(values):
    return sorted(values)[len(values) // 2]


class DiagnosticsTest(unittest.TestCase):
    def test_every_nodelet_reports(self):
        lock = threading.Lock()
        latest = {}
        rates = {}  # every report's input rate, per status
        busiest = {}  # the largest processing time mean reported, per status: a low-priority node
        # may process no frame in some 1-s window, and report a mean of 0 for it

        def callback(msg):
            with lock:
                for status in msg.status:
                    latest[status.name] = {kv.key: kv.value for kv in status.values}
                    if 'input rate (Hz)' in latest[status.name]:
                        rates.setdefault(status.name, []).append(float(latest[status.name]['input rate (Hz)']))
                    if 'processing time mean (ms)' in latest[status.name]:
                        busiest[status.name] = max(busiest.get(status.name, 0.0),
                                                   float(latest[status.name]['processing time mean (ms)']))

        def enough():
            with lock:
                tracker, landmark = latest.get(TRACKER, {}), latest.get(LANDMARK, {})
                return (all(len(rates.get(name, [])) >= REPORTS for name in EXPECTED) and
                        tracker.get('colour ranges from') == 'color_ranges (learned)' and
                        float(tracker.get('colour ranges age (s)', 'inf')) < 5.0 and
                        landmark.get('learned colour classes') == '4')
        # Outputs must have subscribers, or the lazy nodelets rightly report no input.
        keep = [rospy.Subscriber('/camera/%s' % t, rospy.AnyMsg, lambda m: None) for t in ('lines', 'obstacles')]
        rospy.Subscriber('/diagnostics', DiagnosticArray, callback, queue_size=50)
        wait_for(enough, 30 * SLOW, period_s=0.2)
        with lock:
            reports = dict(latest)
            processing = dict(busiest)
            # The median over the reports after the first (start-up) one: one 1-s window may
            # hold a burst of late timer frames (47 Hz once on a loaded machine).
            report_rates = {name: sorted(r[1:] or r) for name, r in rates.items()}
        for name, (share, extra) in EXPECTED.items():
            self.assertIn(name, reports, 'no diagnostics named %r (got %s)' % (name, sorted(reports)))
            values = reports[name]
            for key in COMMON + extra:
                self.assertIn(key, values, '%s lacks %r' % (name, key))
            self.assertGreater(processing.get(name, 0.0), 0.0, '%s never reported a processing time' % name)
        camera_rate = median(report_rates[SIMULATOR])
        self.assertGreater(camera_rate, 0.0, 'the simulator sent no frames')
        self.assertLess(camera_rate, 40.0, 'the simulator runs at 30 Hz: %s' % report_rates[SIMULATOR])
        for name, (share, _) in EXPECTED.items():
            rate = median(report_rates[name])
            self.assertGreaterEqual(rate, share * camera_rate, '%s: input rate %.1f Hz with the camera at %.1f Hz '
                                    '(reports %s)' % (name, rate, camera_rate, report_rates[name]))
            self.assertLess(rate, 40.0, '%s: input rate %.1f Hz (reports %s)' % (name, rate, report_rates[name]))
        tracker = reports[TRACKER]
        self.assertEqual(tracker['colour classes'], '4')
        self.assertEqual(tracker['colour ranges from'], 'color_ranges (learned)')  # learning is on
        self.assertLess(float(tracker['colour ranges age (s)']), 5.0)
        landmark = reports[LANDMARK]
        self.assertEqual(landmark['colour learning'], 'on')
        self.assertEqual(landmark['learned colour classes'], '4')
        rospy.loginfo('diagnostics: %s', ', '.join('%s %.1f Hz' % (n.split(':')[1].strip(), float(reports[n]['input rate (Hz)']))
                                                   for n in EXPECTED))
        rospy.loginfo('input rates per report: %s', report_rates)
        del keep


if __name__ == '__main__':
    rospy.init_node('test_diagnostics')
    rostest.rosrun('rle_vision', 'test_diagnostics', DiagnosticsTest)
