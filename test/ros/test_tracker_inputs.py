#!/usr/bin/env python3
"""rostest: the Tracker run as a standalone node, fed hand-made images. Bad input gets one clear
throttled error and no crash; every supported encoding gives the known blob; colour ranges
swap in over the color_ranges topic and broken ones are refused."""
import sys
import threading
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Image
from rle_vision.msg import BlobArray, ColorRange, ColorRangeArray

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from waiting import SLOW, wait_for, wait_stable  # noqa: E402

WIDTH, HEIGHT = 64, 48
RED_BGR = (40, 40, 210)      # inside the shipped 'red' YUV class
GREEN_BGR = (50, 140, 40)    # the simulator's ground: no shipped class
SQUARE = (10, 8, 20, 12)     # x, y, w, h of the red square


def yuv(r, g, b):
    """OpenCV's fixed-point BGR2YUV (as the tracker computes it)."""
    y = (r * 4899 + g * 9617 + b * 1868 + 8192) >> 14
    u = ((b - y) * 8061 + (128 << 14) + 8192) >> 14
    v = ((r - y) * 14369 + (128 << 14) + 8192) >> 14
    return y, max(0, min(255, u)), max(0, min(255, v))


def pixel_at(x, y, square_bgr=RED_BGR):
    sx, sy, sw, sh = SQUARE
    return square_bgr if sx <= x < sx + sw and sy <= y < sy + sh else GREEN_BGR


def make_image(encoding, width=WIDTH, height=HEIGHT, square_bgr=RED_BGR):
    msg = Image(width=width, height=height, encoding=encoding)
    data = bytearray()
    for y in range(height):
        if encoding in ('bgr8', 'rgb8'):
            for x in range(width):
                b, g, r = pixel_at(x, y, square_bgr)
                data += bytes((b, g, r) if encoding == 'bgr8' else (r, g, b))
        elif encoding == 'mono8':
            data += bytes(200 for _ in range(width))
        elif encoding == 'yuv422':  # UYVY
            for x in range(0, width, 2):
                y0, u0, v0 = yuv(*reversed(pixel_at(x, y, square_bgr)))
                y1, u1, v1 = yuv(*reversed(pixel_at(x + 1, y, square_bgr)))
                data += bytes(((u0 + u1 + 1) // 2, y0, (v0 + v1 + 1) // 2, y1))
        else:
            data += bytes(2 * width)
    msg.step = len(data) // height if height else 0
    msg.data = bytes(data)
    msg.header.frame_id = 'test_camera'
    return msg


class TrackerInputsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lock = threading.Lock()
        cls.blobs = []
        cls.logs = []
        cls.pub_image = rospy.Publisher('cam/image_raw', Image, queue_size=10)
        cls.pub_ranges = rospy.Publisher('cam/color_ranges', ColorRangeArray, queue_size=1, latch=True)
        rospy.Subscriber('cam/blobs', BlobArray, cls.on_blobs, queue_size=100)
        cls.active = []
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        rospy.Subscriber('cam/tracker/active_color_ranges', ColorRangeArray, cls.on_active, queue_size=10)
        # The tracker subscribes lazily, once blobs has a subscriber.
        wait_for(lambda: cls.pub_image.get_num_connections() > 0, 30 * SLOW)

    @classmethod
    def on_blobs(cls, msg):
        with cls.lock:
            cls.blobs.append(msg)

    @classmethod
    def on_active(cls, msg):
        with cls.lock:
            cls.active.append(msg)

    def active_names(self):
        """The class names of the ranges the tracker uses (its latched active_color_ranges)."""
        with self.lock:
            return [r.name for r in self.active[-1].ranges] if self.active else None

    @classmethod
    def on_log(cls, msg):
        if msg.name.endswith('/cam/tracker'):
            with cls.lock:
                cls.logs.append(msg)

    def send(self, image, stamp_s):
        image.header.stamp = rospy.Time.from_sec(stamp_s)
        self.pub_image.publish(image)

    def wait_for_blobs(self, stamp_s, timeout=10.0 * SLOW):
        def found():
            with self.lock:
                return next((m for m in self.blobs if abs(m.header.stamp.to_sec() - stamp_s) < 1e-6), None)
        msg = wait_for(found, timeout, period_s=0.05)
        if msg is None:
            self.fail('no blobs for the image stamped %.3f' % stamp_s)
        return msg

    def logs_matching(self, level, text, expected, timeout=10.0 * SLOW):
        """The log messages of `level` containing `text`, once `expected` of them arrived (or the
        timeout passed) and no more came for a second, so that extra ones are counted too:
        /rosout is another connection than blobs, and may arrive after them."""
        def matching():
            with self.lock:
                return [m for m in self.logs if m.level == level and text in m.msg]
        wait_for(lambda: len(matching()) >= expected, timeout, period_s=0.05)
        wait_stable(lambda: len(matching()), timeout)
        return matching()

    def assert_red_square(self, msg):
        self.assertEqual(len(msg.blobs), 1, msg.blobs)
        blob = msg.blobs[0]
        x, y, w, h = SQUARE
        self.assertEqual(blob.color, 'red')
        self.assertEqual(blob.area, w * h)
        self.assertAlmostEqual(blob.cx, x + (w - 1) / 2.0, places=4)
        self.assertAlmostEqual(blob.cy, y + (h - 1) / 2.0, places=4)
        self.assertEqual((blob.left, blob.top, blob.right, blob.bottom), (x, y, x + w - 1, y + h - 1))

    def test_1_every_supported_encoding_gives_the_known_blob(self):
        for i, encoding in enumerate(('bgr8', 'rgb8', 'yuv422')):
            stamp = 100.0 + i
            self.send(make_image(encoding), stamp)
            msg = self.wait_for_blobs(stamp)
            self.assertEqual(msg.header.frame_id, 'test_camera')
            self.assertEqual((msg.image_width, msg.image_height), (WIDTH, HEIGHT))
            self.assert_red_square(msg)

    def test_2_bad_images_log_one_clear_error_and_the_node_keeps_running(self):
        bad = []
        for _ in range(5):
            bad.append(make_image('bayer_rggb8'))
        bad.append(make_image('16UC1'))
        empty = make_image('bgr8', 0, 0)
        bad.append(empty)
        truncated = make_image('bgr8')
        truncated.data = truncated.data[:100]
        bad.append(truncated)
        for i, image in enumerate(bad):
            self.send(image, 200.0 + i)
        # Then a good frame: the node is alive and right.
        self.send(make_image('bgr8'), 300.0)
        self.assert_red_square(self.wait_for_blobs(300.0))
        # One error per kind of problem (the five Bayer frames log once), each saying what is wrong.
        errors = [m.msg for m in self.logs_matching(Log.ERROR, 'dropping image', 4)]
        self.assertEqual(len(errors), 4, errors)
        self.assertIn("unsupported image encoding 'bayer_rggb8'", errors[0])
        self.assertIn('supported: bgr8', errors[0])
        self.assertIn("unsupported image encoding '16UC1'", errors[1])
        self.assertIn('the image is empty (0x0 pixels)', errors[2])
        self.assertIn('image data has 100 bytes, step x height needs 9216', errors[3])
        with self.lock:
            self.assertFalse(any(abs(m.header.stamp.to_sec() - 200.0) < 1e-6 for m in self.blobs))

    def test_3_mono8_warns_once_that_colour_classes_are_skipped(self):
        for i in range(3):
            self.send(make_image('mono8'), 400.0 + i)
        msg = self.wait_for_blobs(402.0)
        self.assertEqual(len(msg.blobs), 0)  # the shipped classes all constrain chroma
        warnings = self.logs_matching(Log.WARN, 'mono8 images carry no colour', 1)
        self.assertEqual(len(warnings), 1)

    def test_4_color_ranges_swap_in_and_broken_ones_are_refused(self):
        green = ColorRange(name='field', space='RGB', min=[30, 120, 30], max=[70, 160, 70],
                           display_rgb=[0, 255, 0], min_area=1, source='learned')
        self.pub_ranges.publish(ColorRangeArray(ranges=[green]))
        self.assertTrue(wait_for(lambda: self.active_names() == ['field'], 10 * SLOW),
                        'the tracker did not take the field range: it uses %s' % self.active_names())
        self.send(make_image('bgr8'), 500.0)
        msg = self.wait_for_blobs(500.0)
        self.assertEqual([b.color for b in msg.blobs], ['field'])
        self.assertEqual(msg.blobs[0].area, WIDTH * HEIGHT - SQUARE[2] * SQUARE[3])
        broken = ColorRange(name='x', space='LAB', min=[0, 0, 0], max=[255, 255, 255])
        self.pub_ranges.publish(ColorRangeArray(ranges=[broken]))
        errors = self.logs_matching(Log.ERROR, "unknown space 'LAB'", 1)  # refused, said so: the frame comes after
        self.assertEqual(len(errors), 1)
        self.send(make_image('bgr8'), 501.0)
        msg = self.wait_for_blobs(501.0)
        self.assertEqual([b.color for b in msg.blobs], ['field'], 'a broken range set must not replace the good one')
        self.assertEqual(self.active_names(), ['field'])


if __name__ == '__main__':
    rospy.init_node('test_tracker_inputs')
    rostest.rosrun('rle_vision', 'test_tracker_inputs', TrackerInputsTest)
