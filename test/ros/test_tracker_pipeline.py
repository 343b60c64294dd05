#!/usr/bin/env python3
"""rostest: simulator -> Tracker nodelet in one manager. Checks blob values against the
simulator's exact ground truth, frame by frame: headers, centroids, areas, boxes, stable ids,
no false blobs."""
import sys
import threading
import unittest

import rospy
import rostest
from rle_vision.msg import BlobArray, SceneTruth

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from truth_matching import clear_objects, nearest_blob, perimeter, whole_objects  # noqa: E402
from waiting import SLOW, wait_for  # noqa: E402

FRAMES = 90


class TrackerPipelineTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.truth = {}
        self.blobs = {}
        rospy.Subscriber('camera/ground_truth/scene', SceneTruth, self.on_truth, queue_size=200)
        rospy.Subscriber('camera/blobs', BlobArray, self.on_blobs, queue_size=200)

    def on_truth(self, msg):
        with self.lock:
            self.truth[msg.header.stamp] = msg

    def on_blobs(self, msg):
        with self.lock:
            self.blobs[msg.header.stamp] = msg

    def paired_frames(self):
        with self.lock:
            stamps = sorted(set(self.truth) & set(self.blobs))
            return [(self.truth[s], self.blobs[s]) for s in stamps]

    def test_blobs_match_ground_truth(self):
        wait_for(lambda: len(self.paired_frames()) >= FRAMES, 60 * SLOW)
        frames = self.paired_frames()
        self.assertGreaterEqual(len(frames), FRAMES, 'too few frames paired by stamp')

        id_of = {}
        worst = 0.0
        checked = 0
        for truth, blobs in frames:
            self.assertEqual(blobs.header.frame_id, 'camera_optical_frame')
            self.assertEqual((blobs.image_width, blobs.image_height), (640, 480))
            self.assertGreater(blobs.processing_time_ms, 0.0)
            # Every blob lies on a ground-truth object of its own colour: none on ground or sky.
            for b in blobs.blobs:
                on_object = any(o.color == b.color and o.left - 2 <= b.cx <= o.right + 2 and
                                o.top - 2 <= b.cy <= o.bottom + 2 for o in truth.objects if o.area > 0)
                self.assertTrue(on_object, 'false %s blob at %.1f,%.1f' % (b.color, b.cx, b.cy))
            clear = set(o.name for o in clear_objects(truth, min_area=300))
            for o in whole_objects(truth, min_area=300):
                blob, distance = nearest_blob(blobs, o, 3.0)
                self.assertIsNotNone(blob, 'no %s blob for %s (frame %d)' % (o.color, o.name, truth.frame_index))
                if o.name in clear:
                    # Surrounded by ground or sky: the blob is the object to within a pixel.
                    worst = max(worst, distance)
                    self.assertLess(distance, 1.0, '%s centroid off by %.2f px' % (o.name, distance))
                    for ours, theirs in ((blob.left, o.left), (blob.top, o.top), (blob.right, o.right), (blob.bottom, o.bottom)):
                        self.assertLessEqual(abs(int(ours) - int(theirs)), 2, o.name)
                    checked += 1
                else:
                    # Next to another box, blurred two-colour edge pixels belong to neither class.
                    self.assertLess(distance, 2.0, '%s (next to another box) centroid off by %.2f px' % (o.name, distance))
                self.assertLessEqual(abs(blob.area - o.area), perimeter(o), o.name)
                if o.name in id_of:
                    self.assertEqual(blob.id, id_of[o.name], '%s changed id' % o.name)
                    self.assertGreater(blob.age, 0)
                else:
                    id_of[o.name] = blob.id
        self.assertGreaterEqual(len(id_of), 8, 'too few whole objects checked')
        self.assertGreaterEqual(checked, len(frames), 'too few clear objects checked')
        self.assertEqual(len(set(id_of.values())), len(id_of), 'two objects share an id')
        rospy.loginfo('checked %d blobs over %d frames, worst centroid error %.3f px', checked, len(frames), worst)


if __name__ == '__main__':
    rospy.init_node('test_tracker_pipeline')
    rostest.rosrun('rle_vision', 'test_tracker_pipeline', TrackerPipelineTest)
