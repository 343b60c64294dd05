#!/usr/bin/env python3
"""rostest: every live-tunable parameter reaches the nodelet and changes what it does
(opencv_apps once shipped parameters that never arrived). Each test sets a parameter with
dynamic_reconfigure, feeds a synthetic image whose right answer differs between the two
values, and checks the output."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from dynamic_reconfigure.client import Client
from rle_vision.msg import BlobArray, ColorRangeArray, Horizon, LineArray
from sensor_msgs.msg import Image

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from synthetic_images import BgrImage, bgr_from_yuv  # noqa: E402
from waiting import SLOW, ByStamp, wait_for  # noqa: E402

W, H = 320, 240
RED = bgr_from_yuv(90, 106, 220)       # inside colors.yaml's red box
SKY, GROUND = (235, 205, 170), (50, 140, 40)


class LiveTuningTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tracker_image = rospy.Publisher('/tune_tracker/image_raw', Image, queue_size=5)
        cls.blobs = ByStamp('/tune_tracker/blobs', BlobArray, queue_size=20)
        cls.landmark_image = rospy.Publisher('/tune_landmark/image_raw', Image, queue_size=5)
        cls.edges = ByStamp('/tune_landmark/edges', Image, queue_size=20)
        cls.lines = ByStamp('/tune_landmark/lines', LineArray, queue_size=20)
        cls.horizon = ByStamp('/tune_landmark/horizon', Horizon, queue_size=20)
        cls.ranges = ByStamp('/tune_landmark/color_ranges', ColorRangeArray, queue_size=20)
        # Watching the overlay keeps the landmark node on the colour images whatever learning does.
        cls.overlay = ByStamp('/tune_landmark/landmark/debug_image', Image, queue_size=20)
        cls.diagnostics, cls.diagnostics_lock = [], threading.Lock()

        def on_diagnostics(msg):
            with cls.diagnostics_lock:
                cls.diagnostics.extend(s for s in msg.status if s.name.lstrip('/').startswith('tune_landmark/landmark:'))
        rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics, queue_size=50)
        cls.tracker = Client('/tune_tracker/tracker', timeout=30 * SLOW)
        cls.edge_detector = Client('/tune_landmark/edge_detector', timeout=30 * SLOW)
        cls.landmark = Client('/tune_landmark/landmark', timeout=30 * SLOW)
        cls.stamp = rospy.Time(1000)
        # The nodelets subscribe lazily, once their outputs have a reader: frames are sent until
        # each pipeline answers one, so that from then on every frame is sent exactly once
        # (a frame sent twice would count twice for the tracker's tracks).
        warm_up = BgrImage(W, H, (0, 0, 0))
        cls.first_answer(cls.tracker_image, warm_up, [cls.blobs])
        cls.first_answer(cls.landmark_image, warm_up, [cls.lines, cls.horizon, cls.edges, cls.overlay])

    @classmethod
    def first_answer(cls, publisher, image, outputs):
        stamps = []

        def answered():
            return any(all(o.get(s) is not None for o in outputs) for s in stamps)
        deadline = time.time() + 60 * SLOW
        while time.time() < deadline:
            cls.stamp += rospy.Duration(1.0 / 30)
            stamps.append(cls.stamp)
            publisher.publish(image.msg(stamps[-1]))
            if wait_for(answered, 2 * SLOW, period_s=0.02):
                return
        raise AssertionError('no answer on %s to %d frames' % ([o.sub.name for o in outputs], len(stamps)))

    def forget_tracks(self):
        empty = BgrImage(W, H, (0, 0, 0))
        for _ in range(7):  # more than max_missed_frames (5): every track is dropped
            self.track(empty)

    def next_stamp(self):
        LiveTuningTest.stamp += rospy.Duration(1.0 / 30)
        return LiveTuningTest.stamp

    def track(self, image):
        stamp = self.next_stamp()
        self.tracker_image.publish(image.msg(stamp))
        return self.blobs.require(stamp)

    def landmarks(self, image):
        stamp = self.next_stamp()
        self.landmark_image.publish(image.msg(stamp))
        return self.lines.require(stamp), self.horizon.require(stamp), self.edges.require(stamp)

    # --- Tracker -------------------------------------------------------------------------
    def test_tracker_min_area_px(self):
        image = BgrImage(W, H, (0, 0, 0))
        image.fill_rect(20, 20, 30, 30, RED)     # 100 px
        image.fill_rect(100, 100, 120, 120, RED)  # 400 px
        self.tracker.update_configuration({'min_area_px': 1})
        self.assertEqual(sorted(b.area for b in self.track(image).blobs), [100, 400])
        self.tracker.update_configuration({'min_area_px': 200})
        self.assertEqual([b.area for b in self.track(image).blobs], [400])
        self.tracker.update_configuration({'min_area_px': 1})

    def test_tracker_min_track_area_px(self):
        image = BgrImage(W, H, (0, 0, 0))
        image.fill_rect(20, 20, 30, 30, RED)     # 100 px
        image.fill_rect(100, 100, 120, 120, RED)  # 400 px
        self.tracker.update_configuration({'min_track_area_px': 200})
        self.assertEqual([b.area for b in self.track(image).blobs], [400])
        self.tracker.update_configuration({'min_track_area_px': 20})
        self.assertEqual(sorted(b.area for b in self.track(image).blobs), [100, 400])

    def test_tracker_max_regions_per_class(self):
        image = BgrImage(W, H, (0, 0, 0))
        for i, side in enumerate((6, 7, 8, 9, 10, 11)):  # six squares of 36 to 121 px
            image.fill_rect(10 + 40 * i, 50, 10 + 40 * i + side, 50 + side, RED)
        self.tracker.update_configuration({'max_regions_per_class': 3})
        self.assertEqual(sorted(b.area for b in self.track(image).blobs), [81, 100, 121])  # the largest
        self.tracker.update_configuration({'max_regions_per_class': 500})
        self.assertEqual(len(self.track(image).blobs), 6)

    def test_tracker_connectivity(self):
        image = BgrImage(W, H, (0, 0, 0))
        image.fill_rect(100, 100, 120, 120, RED)
        image.fill_rect(120, 120, 140, 140, RED)  # touches the first only at a corner
        self.tracker.update_configuration({'connectivity': 8})
        self.assertEqual(len(self.track(image).blobs), 1)
        self.tracker.update_configuration({'connectivity': 4})
        self.assertEqual(len(self.track(image).blobs), 2)
        self.tracker.update_configuration({'connectivity': 8})

    def square_at(self, x, size=20):
        image = BgrImage(W, H, (0, 0, 0))
        image.fill_rect(x, 100, x + size, 100 + size, RED)
        return image

    def test_tracker_tracking_gate_px(self):
        for gate, same in ((48.0, True), (10.0, False)):
            self.tracker.update_configuration({'tracking_gate_px': gate})
            self.forget_tracks()
            first = self.track(self.square_at(40)).blobs[0].id
            self.assertEqual(self.track(self.square_at(40)).blobs[0].id, first)  # standing still
            jumped = self.track(self.square_at(70)).blobs[0].id  # a 30 px jump
            self.assertEqual(jumped == first, same, 'tracking_gate_px %.0f' % gate)
        self.tracker.update_configuration({'tracking_gate_px': 48.0})

    def test_tracker_max_area_ratio(self):
        self.tracker.update_configuration({'max_area_ratio': 4.0})
        self.forget_tracks()
        first = self.track(self.square_at(150, 20)).blobs[0].id
        self.assertEqual(self.track(self.square_at(150, 30)).blobs[0].id, first)  # 2.25x
        self.tracker.update_configuration({'max_area_ratio': 1.5})
        self.assertNotEqual(self.track(self.square_at(150, 20)).blobs[0].id, first)  # 2.25x again
        self.tracker.update_configuration({'max_area_ratio': 4.0})

    def test_tracker_max_missed_frames(self):
        empty = BgrImage(W, H, (0, 0, 0))
        for missed, same in ((5, True), (1, False)):
            self.tracker.update_configuration({'max_missed_frames': 5})
            self.forget_tracks()
            self.tracker.update_configuration({'max_missed_frames': missed})
            first = self.track(self.square_at(200)).blobs[0].id
            for _ in range(3):
                self.assertEqual(len(self.track(empty).blobs), 0)
            again = self.track(self.square_at(200)).blobs[0].id
            self.assertEqual(again == first, same, 'max_missed_frames %d' % missed)
        self.tracker.update_configuration({'max_missed_frames': 5})

    def test_tracker_velocity_smoothing(self):
        speeds = {}
        for smoothing in (1.0, 0.2):
            self.tracker.update_configuration({'velocity_smoothing': smoothing})
            self.forget_tracks()
            for x in (40, 43, 46, 52, 58):  # 90 px/s (3 px per frame at 30 Hz), then 180 px/s
                blob = self.track(self.square_at(x)).blobs[0]
            speeds[smoothing] = blob.vx
        self.assertAlmostEqual(speeds[1.0], 180.0, delta=1.0)
        self.assertLess(speeds[0.2], 150.0)  # still catching up
        self.tracker.update_configuration({'velocity_smoothing': 0.5})

    # --- EdgeDetector ----------------------------------------------------------------------
    def test_edge_detector_edge_gain(self):
        image = BgrImage(W, H, (100, 100, 100))
        image.fill_rect(160, 0, W, H, (100, 100, 140))  # a step of 40 in red
        peaks = {}
        for gain in (2.0, 5.0):
            self.edge_detector.update_configuration({'edge_gain': gain})
            _, _, edges = self.landmarks(image)
            peaks[gain] = max(edges.data)
        self.assertEqual(peaks[2.0], 80)
        self.assertEqual(peaks[5.0], 200)
        self.edge_detector.update_configuration({'edge_gain': 2.0})

    # --- Landmark --------------------------------------------------------------------------
    def horizon_scene(self, angle_deg=0.0, step=None):
        """Smooth sky above textured ground (the horizon detector weighs both), the boundary
        through (W / 2, 0.4 H)."""
        image = BgrImage(W, H, SKY)
        image.fill_below_line(angle_deg, H * 0.4, step or GROUND)
        image.add_ground_texture(angle_deg, H * 0.4, 12)
        return image

    @staticmethod
    def hough_lines(lines):
        """The lines the Hough found (the horizon's own segment is added with no votes)."""
        return [l for l in lines.lines if l.votes > 0]

    def test_landmark_gray_threshold(self):
        faint = self.horizon_scene(step=(SKY[0], SKY[1], SKY[2] - 40))  # edge value 80 at gain 2
        self.landmark.update_configuration({'gray_threshold': 60})
        hough = self.hough_lines(self.landmarks(faint)[0])
        self.assertEqual(len(hough), 1)
        self.assertAlmostEqual(hough[0].intercept, 96.5, delta=1.0)  # the step between rows 96 and 97
        self.landmark.update_configuration({'gray_threshold': 100})
        lines, horizon, _ = self.landmarks(faint)
        self.assertEqual(self.hough_lines(lines), [])
        # The horizon is weighed on the colours and the frame's own edge statistics, not on the
        # edge classes: it is still there.
        self.assertTrue(horizon.found)
        self.landmark.update_configuration({'gray_threshold': 60})

    def test_landmark_sharp_threshold_and_min_object_px(self):
        scene = self.horizon_scene()
        self.landmark.update_configuration({'min_object_px': 20})
        self.assertEqual(len(self.hough_lines(self.landmarks(scene)[0])), 1)
        self.landmark.update_configuration({'min_object_px': 100000})  # every edge object is noise now
        self.assertEqual(self.hough_lines(self.landmarks(scene)[0]), [])
        self.landmark.update_configuration({'min_object_px': 20})
        # sharp_threshold below gray_threshold is refused: the node keeps working as before.
        self.landmark.update_configuration({'sharp_threshold': 10})
        self.assertEqual(len(self.hough_lines(self.landmarks(scene)[0])), 1)
        self.landmark.update_configuration({'sharp_threshold': 200})

    def test_landmark_min_votes(self):
        # Sampling grows with min_votes (eq. 4) up to max_samples_per_object (2000): the box's
        # four edges share those pairs and none reaches 1000 votes; the lone horizon does.
        scene = self.box_scene()
        self.landmark.update_configuration({'min_votes': 5})
        many = len(self.hough_lines(self.landmarks(scene)[0]))
        self.assertGreaterEqual(many, 5)
        self.landmark.update_configuration({'min_votes': 1000})
        self.assertEqual(len(self.hough_lines(self.landmarks(scene)[0])), 1)
        self.landmark.update_configuration({'min_votes': 5})

    def test_landmark_max_samples_per_object(self):
        scene = self.box_scene()  # the box's four edges are one edge object
        self.landmark.update_configuration({'max_samples_per_object': 2000})
        many = len(self.hough_lines(self.landmarks(scene)[0]))
        self.assertGreaterEqual(many, 5)
        # 10 pairs shared by four edges cannot give each edge 5 votes; the horizon (alone in
        # its object) still gets them.
        self.landmark.update_configuration({'max_samples_per_object': 10, 'max_rounds': 1})
        self.assertEqual(len(self.hough_lines(self.landmarks(scene)[0])), 1)
        self.landmark.update_configuration({'max_samples_per_object': 2000, 'max_rounds': 4})

    def test_landmark_max_refinements_per_frame(self):
        scene = self.box_scene()  # the horizon (the largest edge object) and the box's edges
        self.landmark.update_configuration({'max_refinements_per_frame': 500})
        many = len(self.hough_lines(self.landmarks(scene)[0]))
        self.assertGreaterEqual(many, 5)
        # A budget of one fit: the largest object's line, the horizon between rows 96 and 97;
        # diagnostics say the budget ran out, with the fix.
        self.landmark.update_configuration({'max_refinements_per_frame': 1})
        hough = self.hough_lines(self.landmarks(scene)[0])
        self.assertEqual(len(hough), 1)
        self.assertAlmostEqual(hough[0].intercept, 96.5, delta=1.0)

        def budget_warned():
            with self.diagnostics_lock:
                return [s for s in self.diagnostics if s.level == DiagnosticStatus.WARN and
                        'max_refinements_per_frame ran out' in s.message and
                        int({v.key: v.value for v in s.values}.get('frames whose line budget ran out (total)', 0)) >= 1]
        self.assertTrue(wait_for(budget_warned, 10 * SLOW), 'no budget warning on /diagnostics')
        self.landmark.update_configuration({'max_refinements_per_frame': 500})
        self.assertEqual(len(self.hough_lines(self.landmarks(scene)[0])), many)

    def test_landmark_horizon_max_angle_deg(self):
        tilted = self.horizon_scene(20.0)
        self.landmark.update_configuration({'horizon_max_angle_deg': 40.0})
        horizon = self.landmarks(tilted)[1]
        self.assertTrue(horizon.found)
        self.assertAlmostEqual(horizon.line.theta, 0.349, delta=0.01)
        self.landmark.update_configuration({'horizon_max_angle_deg': 10.0})
        horizon = self.landmarks(tilted)[1]
        # Not the 20-degree boundary: at most the best split the limit allows.
        self.assertFalse(horizon.found and abs(horizon.line.theta - 0.349) < 0.05)
        if horizon.found:
            self.assertLessEqual(abs(horizon.line.theta), math.radians(10.0) + 1e-6)
        self.landmark.update_configuration({'horizon_max_angle_deg': 60.0})

    def test_landmark_horizon_min_confidence(self):
        scene = self.horizon_scene()
        self.landmark.update_configuration({'horizon_min_confidence': 0.5})
        horizon = self.landmarks(scene)[1]
        self.assertTrue(horizon.found)
        self.assertGreater(horizon.confidence, 0.7)
        self.assertLess(horizon.confidence, 1.0)
        self.assertAlmostEqual(horizon.line.intercept, 96.5, delta=1.0)
        # Asking for more confidence than this horizon has: the same horizon, not reported.
        self.landmark.update_configuration({'horizon_min_confidence': 0.5 * (horizon.confidence + 1.0)})
        gated = self.landmarks(scene)[1]
        self.assertFalse(gated.found)
        self.assertAlmostEqual(gated.confidence, horizon.confidence, delta=1e-6)  # reported, only not enough
        self.landmark.update_configuration({'horizon_min_confidence': 0.5})

    def box_scene(self):
        image = self.horizon_scene()
        image.fill_rect(130, 130, 190, 200, bgr_from_yuv(80, 112, 200))  # reddish, off red's centre
        image.add_pattern_noise(4)
        return image

    def learned_red(self, blend):
        """Red's range after one frame of learning from a fresh start with this blend."""
        self.landmark.update_configuration({'learning': False})
        self.landmarks(self.box_scene())  # hands back the configured ranges, resets the learner
        self.landmark.update_configuration({'learning': True, 'learning_blend': blend, 'learning_publish_period_s': 0.0})
        lines, _, _ = self.landmarks(self.box_scene())
        learned = self.ranges.wait(lines.header.stamp)  # the ranges learned on that frame carry its stamp
        self.assertIsNotNone(learned, 'no color_ranges after a frame with learning on')
        return next(r for r in learned.ranges if r.name == 'red')

    def test_landmark_learning_and_blend(self):
        configured_v_centre = (184 + 255) / 2.0
        full = self.learned_red(1.0)
        self.assertEqual(full.source, 'learned')
        partial = self.learned_red(0.25)
        self.assertEqual(partial.source, 'learned')
        shift_full = (full.min[2] + full.max[2]) / 2.0 - configured_v_centre
        shift_partial = (partial.min[2] + partial.max[2]) / 2.0 - configured_v_centre
        self.assertLess(shift_full, -10)  # the box's V (200) is below red's configured centre
        self.assertAlmostEqual(shift_partial / shift_full, 0.25, delta=0.1)
        # Learning off: the configured ranges come back.
        self.landmark.update_configuration({'learning': False})
        self.landmarks(self.box_scene())
        configured = wait_for(lambda: not any(r.source == 'learned' for r in self.ranges.latest().ranges) and
                              self.ranges.latest(), 10 * SLOW)
        self.assertTrue(configured, 'learning off, and the learned ranges stay')
        red = next(r for r in configured.ranges if r.name == 'red')
        self.assertEqual((red.source, list(red.min), list(red.max)), ('config', [30, 85, 184], [150, 128, 255]))
        self.landmark.update_configuration({'learning': True, 'learning_blend': 0.2, 'learning_publish_period_s': 0.5})


if __name__ == '__main__':
    rospy.init_node('test_live_tuning')
    rostest.rosrun('rle_vision', 'test_live_tuning', LiveTuningTest)
