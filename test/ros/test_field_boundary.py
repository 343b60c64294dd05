#!/usr/bin/env python3
"""rostest: a floor (green carpet, textured) below a wall, the edge between them a straight line
at 5 degrees through (160, 100); a yellow square on the floor and one on the wall. The Landmark
node must publish field_boundary along that line, and the Tracker (on_field_classes: yellow)
must drop the yellow blob on the wall, keep the one on the floor with a negative
above_field_px, and count the dropped blobs in diagnostics."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from rle_vision.msg import BlobArray, FieldBoundary
from sensor_msgs.msg import Image

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from synthetic_images import BgrImage, bgr_from_yuv  # noqa: E402
from waiting import SLOW, ByStamp, require  # noqa: E402

W, H = 320, 240
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


if __name__ == '__main__':
    rospy.init_node('test_field_boundary')
    rostest.rosrun('rle_vision', 'test_field_boundary', FieldBoundaryTest)
