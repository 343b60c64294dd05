#!/usr/bin/env python3
"""rostest: a floor (green carpet, textured) below a wall, the edge between them a straight line
at 5 degrees through (160, 100); a yellow square on the floor and one on the wall. The Landmark
node must publish field_boundary along that line, and the Tracker (on_field_classes: yellow)
must drop the yellow blob on the wall, keep the one on the floor with a negative
above_field_px, and count the dropped blobs in diagnostics. Then the light drifts to 55%: the
floor's colour, followed by the Landmark node and published as class 'field' on color_ranges
(learning_field_class), must reach the tracker, whose field blobs keep >= 95% of the floor."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from rle_vision.msg import BlobArray, ColorRangeArray, FieldBoundary
from sensor_msgs.msg import Image

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from synthetic_images import BgrImage, bgr_from_yuv  # noqa: E402
from waiting import SLOW, ByStamp, require  # noqa: E402

W, H = 320, 240
DRIFT_GAIN = 0.55  # the light at the end of the drift
WALL, CARPET = (150, 170, 185), (55, 135, 45)
YELLOW = bgr_from_yuv(170, 60, 155)  # inside colors.yaml's yellow box
ANGLE_DEG, Y_AT_CENTRE = 5.0, 100.0


def true_row(x):
    return Y_AT_CENTRE + math.tan(math.radians(ANGLE_DEG)) * (x - W / 2.0)


def row_on(points, x):
    """The boundary's row at x (linear between its points)."""
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= x <= x1:
            return y0 + (x - x0) * (y1 - y0) / max(x1 - x0, 1e-9)
    return points[0][1] if x < points[0][0] else points[-1][1]


class FieldBoundaryTest(unittest.TestCase):
    def test_boundary_published_and_off_field_blobs_dropped(self):
        image = BgrImage(W, H, WALL)
        image.fill_below_line(ANGLE_DEG, Y_AT_CENTRE, CARPET)
        image.add_ground_texture(ANGLE_DEG, Y_AT_CENTRE, 6)
        image.fill_rect(60, 160, 80, 180, YELLOW)   # on the floor
        image.fill_rect(230, 30, 250, 50, YELLOW)   # on the wall
        pub = rospy.Publisher('/field_test/image_raw', Image, queue_size=5)
        boundaries = ByStamp('/field_test/field_boundary', FieldBoundary)
        blobs = ByStamp('/field_test/blobs', BlobArray)
        lock, dropped = threading.Lock(), []

        def on_diagnostics(msg):
            for s in msg.status:
                if s.name.lstrip('/').startswith('field_test/tracker:'):
                    values = {v.key: v.value for v in s.values}
                    with lock:
                        dropped.append(int(values.get('blobs dropped beyond the field boundary (total)', 0)))
        rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics, queue_size=20)
        stamp = rospy.Time(2000)
        sent = []

        def settled():
            # Frames keep coming (as a camera's do) until one's blobs were filtered by a boundary.
            nonlocal stamp
            stamp += rospy.Duration(0.1)
            pub.publish(image.msg(stamp))
            sent.append(stamp)
            time.sleep(0.1)
            for s in reversed(sent[:-1]):
                b = blobs.get(s)
                if b is not None and b.blobs and all(not math.isnan(x.above_field_px) for x in b.blobs):
                    return s
            return None
        last = require(settled, 60 * SLOW, 'blobs measured against a field boundary')

        boundary = require(boundaries.latest, 10 * SLOW, 'a field_boundary message')
        self.assertTrue(boundary.found, 'no field boundary found on a plain floor below a wall')
        points = [(p.x, p.y) for p in boundary.points]
        self.assertGreaterEqual(len(points), 2)
        errors = [abs(row_on(points, x) - true_row(x)) for x in range(8, W - 8, 8)]
        self.assertLessEqual(max(errors), 3.0, 'boundary %s, errors %s' % (points, errors))

        kept = [b for b in blobs.get(last).blobs if b.color == 'yellow']
        self.assertEqual(len(kept), 1, 'yellow blobs kept: %s' % [(b.cx, b.cy) for b in kept])
        self.assertAlmostEqual(kept[0].cx, 69.5, delta=1.0)   # the one on the floor
        # Its lowest row (179) lies about 82 px below the boundary there.
        self.assertAlmostEqual(kept[0].above_field_px, true_row(69.5) - 179, delta=3.0)
        require(lambda: dropped and dropped[-1] > 0, 10 * SLOW, 'the dropped blobs counted in diagnostics')

    def test_field_colour_follows_a_light_drift(self):
        image = BgrImage(W, H, WALL)
        image.fill_below_line(ANGLE_DEG, Y_AT_CENTRE, CARPET)
        image.add_ground_texture(ANGLE_DEG, Y_AT_CENTRE, 6)
        floor_px = sum(1 for y in range(H) for x in range(W) if y > true_row(x))
        pub = rospy.Publisher('/field_test/image_raw', Image, queue_size=5)
        blobs = ByStamp('/field_test/blobs', BlobArray)
        lock, active = threading.Lock(), []

        def on_active(msg):
            with lock:
                active.append({r.name: r for r in msg.ranges})
        rospy.Subscriber('/field_test/tracker/active_color_ranges', ColorRangeArray, on_active, queue_size=5)
        stamp = rospy.Time(3000)
        # 45% in 12 s (10 Hz): two and a half times as fast as the simulator's drift preset
        # (scene_drift.yaml, 30 s).
        frames = 140
        sent = []

        def send(gain):
            nonlocal stamp
            stamp += rospy.Duration(0.1)
            pub.publish(image.scaled(gain).msg(stamp))
            sent.append(stamp)
            time.sleep(0.1)

        def floor_kept(s):
            b = blobs.get(s)
            return sum(x.area for x in b.blobs if x.color == 'field') / float(floor_px) if b else None
        for i in range(frames):
            send(1.0 - (1.0 - DRIFT_GAIN) * min(1.0, i / (frames - 20.0)))
        early = [floor_kept(s) for s in sent[10:frames - 2]]  # through the drift, once the class reached the tracker

        def settled():
            send(DRIFT_GAIN)
            kept = floor_kept(sent[-2])
            return kept if kept is not None and kept >= 0.95 else None
        kept = require(settled, 30 * SLOW, "the tracker's field blobs on >= 95%% of the floor at %.0f%% light" % (100 * DRIFT_GAIN))
        with lock:
            field = active[-1].get('field') if active else None
        self.assertIsNotNone(field, 'no field class in the active ranges')
        self.assertEqual(field.source, 'learned')
        # The range followed the carpet down: its Y band sits around the dimmed carpet's luma.
        luma = 0.299 * CARPET[2] + 0.587 * CARPET[1] + 0.114 * CARPET[0]
        self.assertTrue(field.min[0] <= DRIFT_GAIN * luma <= field.max[0], 'Y range %d..%d' % (field.min[0], field.max[0]))
        self.assertLess(field.max[0], luma - 6, 'the range did not move down with the light')
        measured = [k for k in early if k is not None]
        rospy.loginfo('floor kept by the field class: %.3f at the end, %.3f at worst through the drift', kept,
                      min(measured or [0]))
        with lock:
            ranges = [(list(a['field'].min), list(a['field'].max)) for a in active if 'field' in a][-3:]
        self.assertGreaterEqual(len(measured), len(early) // 2, 'blobs of too few drift frames arrived')
        self.assertTrue(min(measured) >= 0.95, 'floor kept through the drift: %s; last field ranges %s' % (
            ['%.2f' % k if k is not None else None for k in early], ranges))


if __name__ == '__main__':
    rospy.init_node('test_field_boundary')
    rostest.rosrun('rle_vision', 'test_field_boundary', FieldBoundaryTest)
