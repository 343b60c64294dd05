#!/usr/bin/env python3
"""rostest: bad input to every node of the pipeline (Tracker, EdgeDetector, Landmark,
GroundProjector). Wrong encodings, empty images, images whose step and data disagree, an
8000x8000 image, broken colour ranges and NaN or out-of-range parameters each get one clear
error naming the problem (once per kind, not once per frame); the nodes keep running and the
next good frame gives the right answer."""
import glob
import math
import os
import sys
import threading
import time
import unittest

import rospkg
import rospy
import rostest
from dynamic_reconfigure.client import Client
from rosgraph_msgs.msg import Log
from rle_vision.msg import BlobArray, ColorRange, ColorRangeArray, Horizon
from sensor_msgs.msg import Image

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from synthetic_images import BgrImage, bgr_from_yuv  # noqa: E402
from waiting import SLOW, ByStamp, wait_for, wait_stable  # noqa: E402

NS = '/bad'
W, H = 320, 240
HORIZON_Y = 100                       # sky above, ground from this row down
RED = bgr_from_yuv(90, 106, 220)      # inside colors.yaml's red box
SKY, GROUND = (235, 205, 170), (50, 140, 40)
SQUARE = (140, 150, 40, 30)           # x, y, w, h of the red box on the ground


def good_frame():
    image = BgrImage(W, H, SKY)
    image.fill_rect(0, HORIZON_Y, W, H, GROUND)
    image.add_ground_texture(0.0, HORIZON_Y - 1, 12)  # real ground is textured, the sky smooth
    x, y, w, h = SQUARE
    image.fill_rect(x, y, x + w, y + h, RED)
    return image


def raw_image(encoding, width, height, step, data_len):
    msg = Image(width=width, height=height, encoding=encoding, step=step)
    msg.data = bytes(data_len)
    msg.header.frame_id = 'camera_optical_frame'
    return msg


def node_log_lines(node_name, text):
    """Lines containing `text` in the roslaunch log file of `node_name` (its name with '/' as
    '-'): a node started with output="log" writes its standard output there (bad_input.test
    sends its stderr along), whoever listens on /rosout, so a warning logged at start-up before
    this test connected is there."""
    pattern = os.path.join(rospkg.get_log_dir(), rospy.get_param('/run_id'), '%s-*-stdout.log' % node_name.strip('/').replace('/', '-'))
    lines = []
    for path in glob.glob(pattern):
        with open(path, errors='replace') as f:
            lines += [line for line in f if text in line]
    return lines


class BadInputTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.log_lock = threading.Lock()
        cls.logs = []
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        cls.pub_image = rospy.Publisher(NS + '/image_raw', Image, queue_size=5)
        cls.pub_edges = rospy.Publisher(NS + '/edges', Image, queue_size=5)
        cls.pub_ranges = rospy.Publisher(NS + '/color_ranges', ColorRangeArray, queue_size=1, latch=True)
        cls.blobs = ByStamp(NS + '/blobs', BlobArray)
        cls.edges = ByStamp(NS + '/edges', Image)
        cls.horizon = ByStamp(NS + '/horizon', Horizon)
        cls.tracker = Client(NS + '/tracker', timeout=30 * SLOW)
        cls.edge_detector = Client(NS + '/edge_detector', timeout=30 * SLOW)
        cls.landmark = Client(NS + '/landmark', timeout=30 * SLOW)
        cls.ground = Client(NS + '/ground_projector', timeout=30 * SLOW)
        wait_for(lambda: cls.pub_image.get_num_connections() > 0 and cls.pub_edges.get_num_connections() > 0, 30 * SLOW)
        cls.next_stamp = 1000

    @classmethod
    def on_log(cls, msg):
        with cls.log_lock:
            cls.logs.append(msg)

    def stamp(self):
        BadInputTest.next_stamp += 1
        return rospy.Time(BadInputTest.next_stamp)

    def logs_of(self, source, level, text, process=NS + '/vision_manager'):
        """Messages logged from one nodelet's source file (the nodelets share the manager's
        process, so rosout's node name does not tell them apart)."""
        with self.log_lock:
            return [m.msg for m in self.logs if m.name == process and m.file.endswith(source) and
                    m.level == level and text in m.msg]

    def wait_for_log(self, node, level, text, timeout_s=10.0 * SLOW, process=NS + '/vision_manager'):
        found = wait_for(lambda: self.logs_of(node, level, text, process), timeout_s, period_s=0.05)
        if found:
            return found
        with self.log_lock:
            seen = [(m.name, m.file, m.msg) for m in self.logs if m.level >= Log.WARN]
        self.fail('%s logged no %s containing %r; warnings and errors seen: %s' % (node, level, text, seen))

    def assert_logged_once(self, node, level, text, what):
        """Exactly one message: counted once no more have come for a while (the frames that
        could log it were all handled before the good frame that follows them)."""
        count = wait_stable(lambda: len(self.logs_of(node, level, text)), 10 * SLOW)
        self.assertEqual(count, 1, '%s: %s must be logged once, got %d' % (node, what, count))

    def answered_good_frame(self):
        """Publishes the good frame (again, under a new stamp, while no answer comes: a nodelet
        subscribes lazily, and the landmark keeps only the newest frame) until one stamp has its
        blobs, edges and horizon; returns them."""
        stamps = []

        def answer():
            for stamp in stamps:
                outputs = (self.blobs.get(stamp), self.edges.get(stamp), self.horizon.get(stamp))
                if all(o is not None for o in outputs):
                    return outputs
            return None
        image = good_frame()
        deadline = time.time() + 30 * SLOW
        while time.time() < deadline:
            stamps.append(self.stamp())
            self.pub_image.publish(image.msg(stamps[-1]))
            outputs = wait_for(answer, 5 * SLOW, period_s=0.02)
            if outputs:
                return outputs
        self.fail('no blobs, edges and horizon for any of %d good frames' % len(stamps))

    def send_good_frame_and_check(self):
        """Every node is alive and right: the red box, edges at the horizon, the horizon."""
        blobs, edges, horizon = self.answered_good_frame()
        self.assertEqual([b.color for b in blobs.blobs], ['red'])
        x, y, w, h = SQUARE
        blob = blobs.blobs[0]
        self.assertEqual(blob.area, w * h)
        self.assertEqual((blob.left, blob.top, blob.right, blob.bottom), (x, y, x + w - 1, y + h - 1))
        self.assertEqual((edges.width, edges.height, edges.encoding), (W, H, 'mono8'))
        self.assertGreater(edges.data[HORIZON_Y * W + 20], 60)  # the sky/ground step
        self.assertEqual(edges.data[50 * W + 20], 0)            # flat sky
        self.assertTrue(horizon.found)
        # The step lies between rows HORIZON_Y - 1 and HORIZON_Y.
        self.assertLess(abs(math.degrees(horizon.line.theta)), 1.0)
        self.assertLess(abs(horizon.line.intercept - (HORIZON_Y - 0.5)), 1.5)

    def check_bad_images(self, publisher, cases, nodes):
        """Each case: (name, message, copies, expected text). Every node in `nodes` must log
        the text exactly once, produce nothing for the bad stamps, and handle the good frame."""
        bad_stamps = []
        for name, msg, copies, text in cases:
            for _ in range(copies):
                stamp = self.stamp()
                msg.header.stamp = stamp
                publisher.publish(msg)
                bad_stamps.append(stamp)
                time.sleep(0.3)  # paced, so that copies reach the nodes as separate frames
            for node in nodes:
                found = self.wait_for_log(node, Log.ERROR, text)
                self.assertIn('dropping', found[0])
        self.send_good_frame_and_check()
        for name, _, copies, text in cases:
            for node in nodes:
                self.assert_logged_once(node, Log.ERROR, text, '%s (%d frames)' % (name, copies))
        for stamp in bad_stamps:
            self.assertIsNone(self.blobs.get(stamp))
            self.assertIsNone(self.horizon.get(stamp))

    def test_1_good_frame_before_anything_bad(self):
        self.send_good_frame_and_check()

    def test_2_bad_camera_images(self):
        row = W * 3
        cases = [
            ('wrong encoding', raw_image('bayer_rggb8', W, H, W, W * H), 3,
             "unsupported image encoding 'bayer_rggb8'"),
            ('zero size', raw_image('bgr8', 0, 0, 0, 0), 3, 'the image is empty (0x0 pixels)'),
            ('step below the row size', raw_image('bgr8', W, H, row - 2, row * H), 3,
             'image step %d is smaller than width x bytes per pixel (%d)' % (row - 2, row)),
            ('data shorter than step x height', raw_image('bgr8', W, H, row, row * H - 1), 3,
             'image data has %d bytes, step x height needs %d' % (row * H - 1, row * H)),
            ('8000x8000', raw_image('bgr8', 8000, 8000, 24000, 24000 * 8000), 1,
             'the image is 8000x8000 pixels, more than the 16777216 (4096x4096) processed'),
        ]
        self.check_bad_images(self.pub_image, cases, ['tracker_nodelet.cpp', 'edge_detector_nodelet.cpp'])

    def test_3_bad_edge_images(self):
        cases = [
            ('colour edges', raw_image('bgr8', W, H, W * 3, W * H * 3), 2,
             'edge images must be mono8 (the EdgeDetector\'s output), got bgr8'),
            ('zero size', raw_image('mono8', W, 0, W, 0), 2, 'the image is empty (320x0 pixels)'),
            ('data shorter than step x height', raw_image('mono8', W, H, W, 100), 2,
             'image data has 100 bytes, step x height needs %d' % (W * H)),
            ('8000x8000', raw_image('mono8', 8000, 8000, 8000, 8000 * 8000), 1,
             'the image is 8000x8000 pixels, more than the 16777216'),
        ]
        self.check_bad_images(self.pub_edges, cases, ['landmark_nodelet.cpp'])

    def test_4_broken_color_ranges_are_refused(self):
        good = dict(space='YUV', display_rgb=[255, 0, 0], min_area=1, source='learned')
        inverted = ColorRange(name='red', min=[45, 140, 160], max=[160, 120, 235], **good)
        unknown = ColorRange(name='red', space='LAB', min=[0, 0, 0], max=[255, 255, 255], display_rgb=[1, 2, 3])
        for ranges, text in (([inverted], "colour class 'red': min 140 > max 120 on YUV U"),
                             ([unknown], "colour range 'red' has unknown space 'LAB' (use YUV, RGB or HSV)")):
            for _ in range(3):
                self.pub_ranges.publish(ColorRangeArray(ranges=ranges))
                time.sleep(0.2)
            self.wait_for_log('tracker_nodelet.cpp', Log.ERROR, text)
            self.send_good_frame_and_check()  # the configured classes still apply
            self.assert_logged_once('tracker_nodelet.cpp', Log.ERROR, text, 'a broken range set sent 3 times')

    def test_5_nan_and_out_of_range_parameters(self):
        nan = float('nan')
        # NaN passes dynamic_reconfigure's clamping: each node refuses it and says so; the
        # configuration it returns is the one in effect.
        config = self.tracker.update_configuration({'tracking_gate_px': nan})
        self.assertEqual(config['tracking_gate_px'], 48.0)
        self.wait_for_log('tracker_nodelet.cpp', Log.WARN, 'not a finite number')
        config = self.edge_detector.update_configuration({'edge_gain': nan})
        self.assertEqual(config['edge_gain'], 2.0)
        self.wait_for_log('edge_detector_nodelet.cpp', Log.WARN, 'edge_gain must be a finite number > 0: keeping 2.000')
        config = self.landmark.update_configuration({'min_line_length_px': nan})
        self.assertEqual(config['min_line_length_px'], 30.0)
        self.wait_for_log('landmark_nodelet.cpp', Log.WARN, 'refusing landmark parameters')
        config = self.ground.update_configuration({'camera_height_m': nan})
        self.assertEqual(config['camera_height_m'], 0.45)
        self.wait_for_log('ground_projector_nodelet.cpp', Log.WARN, 'refusing ground projector parameters')
        # Out of range: clamped to the limit (dynamic_reconfigure's rule), never used as given.
        config = self.tracker.update_configuration({'min_area_px': -5})
        self.assertEqual(config['min_area_px'], 1)
        config = self.edge_detector.update_configuration({'edge_gain': -3.0})
        self.assertEqual(config['edge_gain'], 0.05)
        self.edge_detector.update_configuration({'edge_gain': 2.0})
        self.send_good_frame_and_check()

    def test_6_bad_start_up_parameters_are_reported_and_not_used(self):
        # bad_input.test starts a second tracker with min_area_px -5, tracking_gate_px NaN and
        # max_missed_frames "many". It warns while it starts, perhaps before this test is
        # connected to its /rosout: the warnings are read from its console log.
        node = '/bad_params/tracker'
        for text in (node + '/min_area_px = -5 is outside [1, 1000000]: using 1',
                     node + "/tracking_gate_px must be of type double, got 'nan'",
                     node + "/max_missed_frames must be of type int, got 'many'"):
            found = wait_for(lambda: node_log_lines(node, text), 30 * SLOW, period_s=0.2)
            self.assertTrue(found, '%s did not warn %r (log files: %s)' % (node, text, node_log_lines(node, '')[-5:]))
            self.assertIn('WARN', found[0])
        config = Client(node, timeout=30 * SLOW).get_configuration(timeout=10 * SLOW)
        self.assertEqual(config['min_area_px'], 1)
        self.assertEqual(config['tracking_gate_px'], 48.0)
        self.assertEqual(config['max_missed_frames'], 5)


if __name__ == '__main__':
    rospy.init_node('test_bad_input')
    rostest.rosrun('rle_vision', 'test_bad_input', BadInputTest)
