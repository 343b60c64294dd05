#!/usr/bin/env python3
"""rostest: every nodelet of the demo graph reports on /diagnostics: input rate, processing
time (mean, max), frames dropped, and the age of the colour ranges (tracker and landmark)."""
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray

EXPECTED = {  # status name -> (lowest plausible input rate in Hz, extra keys)
    'camera/simulator: simulator': (20.0, ['frames published']),
    'camera/tracker: tracker': (20.0, ['colour classes', 'colour ranges from', 'colour ranges age (s)']),
    'camera/edge_detector: edge detector': (20.0, []),
    'camera/landmark: landmark': (5.0, ['colour learning', 'learned colour classes', 'colour ranges age (s)']),
    'camera/ground_projector: ground projector': (20.0, []),
}
COMMON = ['input rate (Hz)', 'processing time mean (ms)', 'processing time max (ms)',
          'frames dropped (since last report)', 'frames dropped (total)']


class DiagnosticsTest(unittest.TestCase):
    def test_every_nodelet_reports(self):
        lock = threading.Lock()
        latest = {}
        rates = {}  # every report's input rate, per status

        def callback(msg):
            with lock:
                for status in msg.status:
                    latest[status.name] = {kv.key: kv.value for kv in status.values}
                    if 'input rate (Hz)' in latest[status.name]:
                        rates.setdefault(status.name, []).append(float(latest[status.name]['input rate (Hz)']))
        # Outputs must have subscribers, or the lazy nodelets rightly report no input.
        keep = [rospy.Subscriber('/camera/%s' % t, rospy.AnyMsg, lambda m: None) for t in ('lines', 'obstacles')]
        rospy.Subscriber('/diagnostics', DiagnosticArray, callback, queue_size=50)
        time.sleep(6.0)  # a few 1-s reports at full rate
        with lock:
            reports = dict(latest)
            report_rates = {name: sorted(r) for name, r in rates.items()}
        for name, (min_rate, extra) in EXPECTED.items():
            self.assertIn(name, reports, 'no diagnostics named %r (got %s)' % (name, sorted(reports)))
            values = reports[name]
            for key in COMMON + extra:
                self.assertIn(key, values, '%s lacks %r' % (name, key))
            # The median over the reports: one 1-s window may hold a burst of late timer frames
            # (47 Hz once on a loaded machine); counting every frame twice would give ~60 in all.
            rate = report_rates[name][len(report_rates[name]) // 2]
            self.assertGreater(rate, min_rate, '%s: input rate %.1f Hz (reports %s)' % (name, rate, report_rates[name]))
            self.assertLess(rate, 40.0, '%s: input rate %.1f Hz (reports %s)' % (name, rate, report_rates[name]))
            self.assertGreater(float(values['processing time mean (ms)']), 0.0, name)
        tracker = reports['camera/tracker: tracker']
        self.assertEqual(tracker['colour classes'], '4')
        self.assertEqual(tracker['colour ranges from'], 'color_ranges (learned)')  # learning is on
        self.assertLess(float(tracker['colour ranges age (s)']), 5.0)
        landmark = reports['camera/landmark: landmark']
        self.assertEqual(landmark['colour learning'], 'on')
        self.assertEqual(landmark['learned colour classes'], '4')
        rospy.loginfo('diagnostics: %s', ', '.join('%s %.1f Hz' % (n.split(':')[1].strip(), float(reports[n]['input rate (Hz)']))
                                                   for n in EXPECTED))
        rospy.loginfo('input rates per report: %s', report_rates)
        del keep


if __name__ == '__main__':
    rospy.init_node('test_diagnostics')
    rostest.rosrun('rle_vision', 'test_diagnostics', DiagnosticsTest)
