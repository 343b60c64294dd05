#!/usr/bin/env python3
"""rostest: simulator -> pipeline (Tracker, EdgeDetector, Landmark in one manager). Checks the
horizon and the lines against the simulator's exact ground truth frame by frame, the markers,
and that the tracker keeps every frame while the landmark node runs."""
import math
import sys
import threading
import unittest

import rospy
import rostest
from rle_vision.msg import BlobArray, Horizon, LineArray, SceneTruth
from visualization_msgs.msg import MarkerArray

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from truth_matching import line_angle_difference, near_segment, segment_length, store_by_stamp  # noqa: E402
from waiting import SLOW, wait_for  # noqa: E402

FRAMES = 60


class LandmarkPipelineTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.truth, self.horizons, self.lines, self.blobs = {}, {}, {}, {}
        self.markers = []
        rospy.Subscriber('camera/ground_truth/scene', SceneTruth, store_by_stamp(self.lock, self.truth), queue_size=300)
        rospy.Subscriber('camera/horizon', Horizon, store_by_stamp(self.lock, self.horizons), queue_size=300)
        rospy.Subscriber('camera/lines', LineArray, store_by_stamp(self.lock, self.lines), queue_size=300)
        rospy.Subscriber('camera/blobs', BlobArray, store_by_stamp(self.lock, self.blobs), queue_size=300)
        rospy.Subscriber('camera/landmark/markers', MarkerArray, self.on_markers, queue_size=10)

    def on_markers(self, msg):
        with self.lock:
            self.markers.append(msg)

    def test_horizon_and_lines_match_ground_truth(self):
        def enough():
            with self.lock:
                return len(set(self.truth) & set(self.horizons) & set(self.lines)) >= FRAMES
        wait_for(enough, 90 * SLOW, period_s=0.2)
        with self.lock:
            stamps = sorted(set(self.truth) & set(self.horizons) & set(self.lines))
            frames = [(self.truth[s], self.horizons[s], self.lines[s]) for s in stamps]
            truth_stamps = sorted(self.truth)
            blob_stamps = set(self.blobs)
            markers = list(self.markers)
        self.assertGreaterEqual(len(frames), FRAMES, 'too few landmark frames paired with ground truth by stamp')

        angle_errors, roll_errors, pitch_errors = [], [], []
        truths = found = detections = correct = 0
        for truth, horizon, lines in frames:
            self.assertEqual(horizon.header.frame_id, 'camera_optical_frame')
            self.assertTrue(horizon.found, 'no horizon in frame %d' % truth.frame_index)
            angle_errors.append(math.degrees(line_angle_difference(horizon.line.theta, truth.horizon.theta)))
            self.assertLess(abs(horizon.line.intercept - truth.horizon.intercept), 2.0)
            roll_errors.append(abs(math.degrees(horizon.roll - truth.camera_roll)))
            pitch_errors.append(abs(math.degrees(horizon.pitch - truth.camera_pitch)))  # camera_info present
            self.assertGreater(horizon.confidence, 0.5)
            required = [e for e in truth.edges if segment_length(e) >= 30]
            truths += len(required)
            found += sum(any(near_segment(l, e, 2.0, 2.0) for l in lines.lines) for e in required)
            detections += len(lines.lines)
            correct += sum(any(near_segment(l, e, 2.0, 2.0) for e in truth.edges) for l in lines.lines)
            for l in lines.lines:
                self.assertGreater(l.support, 0)
                if l.votes == 0:  # the horizon's own segment, added where no Hough line covers it
                    self.assertEqual((l.theta, l.x1, l.y1), (horizon.line.theta, horizon.line.x1, horizon.line.y1))
                else:
                    self.assertGreaterEqual(l.votes, 5)
        median = lambda v: sorted(v)[len(v) // 2]  # noqa: E731
        recall, precision = found / float(truths), correct / float(detections)
        rospy.loginfo('%d frames: horizon angle error median %.3f deg, roll %.3f deg, pitch %.3f deg; '
                      'line recall %.3f precision %.3f', len(frames), median(angle_errors), median(roll_errors),
                      median(pitch_errors), recall, precision)
        self.assertLess(median(angle_errors), 0.5)
        self.assertLess(median(roll_errors), 0.5)
        self.assertLess(median(pitch_errors), 0.5)
        self.assertGreater(recall, 0.8)
        self.assertGreater(precision, 0.8)
        # The tracker kept (nearly) every frame while the landmark node ran beside it. On a
        # loaded 2-core machine a late tracker callback can lose a frame to a newer one (queue
        # size 1): allow 3%, report the count.
        # From the first frame with blobs: the simulator starts before the tracker subscribes.
        covered = [s for s in truth_stamps if max(truth_stamps[0], min(blob_stamps)) <= s <= stamps[-1]]
        missing = [s for s in covered if s not in blob_stamps]
        rospy.loginfo('tracker frames without blobs: %d of %d', len(missing), len(covered))
        self.assertLessEqual(len(missing), 0.03 * len(covered), '%d of %d frames have no blobs' % (len(missing), len(covered)))
        # rviz markers: line lists in the image's frame.
        self.assertTrue(markers, 'no markers published')
        namespaces = set(m.ns for a in markers for m in a.markers)
        self.assertIn('lines', namespaces)
        self.assertIn('horizon', namespaces)
        self.assertEqual(markers[-1].markers[0].header.frame_id, 'camera_optical_frame')


if __name__ == '__main__':
    rospy.init_node('test_landmark_pipeline')
    rostest.rosrun('rle_vision', 'test_landmark_pipeline', LandmarkPipelineTest)
