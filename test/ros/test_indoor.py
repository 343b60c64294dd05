#!/usr/bin/env python3
"""rostest: indoors (a carpet with white field lines, the camera pitched down, no sky in view).
Long straight lines cross the image, but nothing looks like sky above ground: the horizon is
never reported. The tracker still finds the boxes and the landmark node the field lines."""
import sys
import threading
import unittest

import rospy
import rostest
from rle_vision.msg import BlobArray, Horizon, LineArray, SceneTruth

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from truth_matching import near_segment, nearest_blob, segment_length, store_by_stamp, whole_objects  # noqa: E402
from waiting import SLOW, wait_for  # noqa: E402

FRAMES = 40


class IndoorTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.truth, self.horizons, self.lines, self.blobs = {}, {}, {}, {}
        rospy.Subscriber('camera/ground_truth/scene', SceneTruth, store_by_stamp(self.lock, self.truth), queue_size=300)
        rospy.Subscriber('camera/horizon', Horizon, store_by_stamp(self.lock, self.horizons), queue_size=300)
        rospy.Subscriber('camera/lines', LineArray, store_by_stamp(self.lock, self.lines), queue_size=300)
        rospy.Subscriber('camera/blobs', BlobArray, store_by_stamp(self.lock, self.blobs), queue_size=300)

    def frames(self):
        def paired():
            with self.lock:
                stamps = sorted(set(self.truth) & set(self.horizons) & set(self.lines) & set(self.blobs))
                if len(stamps) >= FRAMES:
                    return [(self.truth[s], self.horizons[s], self.lines[s], self.blobs[s]) for s in stamps]
            return None
        frames = wait_for(paired, 100 * SLOW, period_s=0.2)
        if not frames:
            self.fail('fewer than %d frames with truth, horizon, lines and blobs' % FRAMES)
        return frames

    def test_no_horizon_but_blobs_and_lines(self):
        frames = self.frames()
        highest = 0.0
        truths = found = detections = correct = objects = tracked = 0
        for truth, horizon, lines, blobs in frames:
            self.assertFalse(truth.horizon_visible)
            self.assertFalse(horizon.found, 'a horizon indoors in frame %d (confidence %.2f)'
                             % (truth.frame_index, horizon.confidence))
            highest = max(highest, horizon.confidence)
            required = [e for e in truth.edges if segment_length(e) >= 30]
            truths += len(required)
            found += sum(any(near_segment(l, e, 2.0, 2.0) for l in lines.lines) for e in required)
            detections += len(lines.lines)
            correct += sum(any(near_segment(l, e, 2.0, 2.0) for e in truth.edges) for l in lines.lines)
            for obj in whole_objects(truth, 200):  # boxes stand on field lines: not "clear"
                if obj.color == 'line':
                    continue
                objects += 1
                tracked += nearest_blob(blobs, obj, 8.0)[0] is not None
        recall, precision = found / float(max(truths, 1)), correct / float(max(detections, 1))
        rospy.loginfo('indoors, %d frames: highest horizon confidence %.2f; line recall %.3f precision %.3f '
                      '(%.1f lines per frame); boxes tracked %d of %d', len(frames), highest, recall, precision,
                      detections / float(len(frames)), tracked, objects)
        self.assertLess(highest, 0.5)
        self.assertGreater(truths, 5 * len(frames))
        self.assertGreater(recall, 0.6)
        self.assertGreater(precision, 0.6)
        self.assertGreater(objects, len(frames))
        self.assertGreaterEqual(tracked, 0.95 * objects)


if __name__ == '__main__':
    rospy.init_node('test_indoor')
    rostest.rosrun('rle_vision', 'test_indoor', IndoorTest)
