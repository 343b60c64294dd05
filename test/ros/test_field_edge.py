#!/usr/bin/env python3
"""rostest: the simulated hall (a carpet 6 m x 5 m, walls and people beyond it, a biped's gait,
the camera's true pose on tf) through the pipeline to the GroundProjector. Its field_edge (the
nearest field edge per bearing, in base_link) must lie on the carpet's border: median distance
under 3% of the range, 90% of the bearings under 6%; and its marker must draw the same edge."""
import math
import sys
import threading
import unittest

import rospy
import rostest
import yaml
from sensor_msgs.msg import LaserScan
from visualization_msgs.msg import Marker

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from waiting import SLOW, require  # noqa: E402

SCANS = 20  # 2 s of the 10 Hz gait


def to_border(field, x, y):
    """Distance of a ground point to the border of the field rectangle."""
    dx = min(abs(x - field['x_min_m']), abs(x - field['x_max_m']))
    dy = min(abs(y - field['y_min_m']), abs(y - field['y_max_m']))
    return min(dx, dy)


class FieldEdgeTest(unittest.TestCase):
    def test_field_edge_lies_on_the_carpets_border(self):
        with open(rospy.get_param('~scene_file')) as f:
            field = yaml.safe_load(f)['field']
        lock, scans, markers = threading.Lock(), [], []

        def on_scan(msg):
            with lock:
                scans.append(msg)

        def on_marker(msg):
            with lock:
                markers.append(msg)
        rospy.Subscriber('camera/field_edge', LaserScan, on_scan, queue_size=50)
        rospy.Subscriber('camera/ground_projector/field_edge_marker', Marker, on_marker, queue_size=50)

        def enough():
            with lock:
                with_ranges = [s for s in scans if any(math.isfinite(r) for r in s.ranges)]
                return with_ranges if len(with_ranges) >= SCANS and markers else None
        placed = require(enough, 60 * SLOW, '%d field_edge scans with ranges, and a marker' % SCANS)
        errors, bearings = [], []
        for scan in placed[:SCANS]:
            self.assertEqual(scan.header.frame_id, 'base_link')
            self.assertAlmostEqual(scan.angle_increment, math.radians(1.0), places=5)
            finite = [(scan.angle_min + i * scan.angle_increment, r) for i, r in enumerate(scan.ranges) if math.isfinite(r)]
            bearings.append(len(finite))
            for bearing, r in finite:
                errors.append(to_border(field, r * math.cos(bearing), r * math.sin(bearing)) / r)
        errors.sort()
        median, p90 = errors[len(errors) // 2], errors[len(errors) * 9 // 10]
        rospy.loginfo('field edge on the ground: %d bearings, distance to the border / range: median %.3f, 90%% %.3f',
                      len(errors), median, p90)
        # A 70 degree view in 1 degree bins: most bearings see the edge.
        self.assertGreaterEqual(min(bearings), 40, 'bearings with an edge per scan: %s' % bearings)
        self.assertLess(median, 0.03, 'median %.3f' % median)
        self.assertLess(p90, 0.06, '90%% %.3f' % p90)
        with lock:
            strip = next(m for m in reversed(markers) if m.action == Marker.ADD)
        self.assertEqual(strip.header.frame_id, 'base_link')
        self.assertEqual(strip.type, Marker.LINE_STRIP)
        on_border = [to_border(field, p.x, p.y) / math.hypot(p.x, p.y) for p in strip.points]
        self.assertGreaterEqual(len(on_border), 40)
        self.assertLess(sorted(on_border)[len(on_border) // 2], 0.03)


if __name__ == '__main__':
    rospy.init_node('test_field_edge')
    rostest.rosrun('rle_vision', 'test_field_edge', FieldEdgeTest)
