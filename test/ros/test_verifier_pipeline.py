#!/usr/bin/env python3
"""rostest: a verifier in the running pipeline. rle_vision_train makes one from synthetic
labelled frames (a shaded ball among an upright bar and a ragged patch of the same yellow); a
colours file names it (verifier_file, min_score; the class's range taken from the model); then
pipeline.launch runs with that file. On frames the training never saw, the tracker publishes the
ball with its score (>= min_score) and not the bar or the patch, scores no other class (NaN), and
/diagnostics counts the candidates it rejected."""
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import unittest

import cv2
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray
from sensor_msgs.msg import Image
from rle_vision.msg import BlobArray

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from waiting import SLOW, require, wait_for  # noqa: E402

CAMERA = 'verifier_cam'
TEST_FRAMES = 8


def ball_box(label_path, width, height):
    """The YOLO box of the ball (class 0) as (left, top, right, bottom) pixels."""
    with open(label_path) as f:
        _, cx, cy, w, h = (float(v) for v in f.readline().split())
    return ((cx - w / 2) * width, (cy - h / 2) * height, (cx + w / 2) * width, (cy + h / 2) * height)


def image_msg(bgr, stamp):
    msg = Image()
    msg.header.stamp = stamp
    msg.header.frame_id = 'camera'
    msg.height, msg.width = bgr.shape[:2]
    msg.encoding = 'bgr8'
    msg.step = msg.width * 3
    msg.data = bgr.tobytes()
    return msg


class VerifierPipelineTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix='rle_vision_verifier_')
        for folder, frames, seed in (('train', 40, 1), ('unseen', TEST_FRAMES, 99)):
            os.makedirs(os.path.join(self.dir, folder))
            subprocess.run(['rosrun', 'rle_vision', 'verifier_scene_frames', os.path.join(self.dir, folder), str(frames),
                            str(seed)], check=True)
        model = os.path.join(self.dir, 'ball_verifier.yml.gz')
        # One folder, one light: the same-coloured shapes are candidates only with the range widened.
        subprocess.run(['rosrun', 'rle_vision', 'rle_vision_train', '--class', 'ball', '--label-class', '0', '--widen', '16',
                        '--output', model, os.path.join(self.dir, 'train')], check=True, stdout=subprocess.DEVNULL)
        self.colors = os.path.join(self.dir, 'colors.yaml')
        with open(self.colors, 'w') as f:
            f.write('classes:\n'
                    '  - name: ball\n    verifier_file: ball_verifier.yml.gz\n    min_score: 0.5\n'
                    '  - name: goal\n    min: [0, 170, 0]\n    max: [255, 255, 110]\n    min_area_px: 20\n')

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_the_ball_is_kept_with_its_score_and_same_coloured_shapes_are_dropped(self):
        lock = threading.Lock()
        blobs, statuses = {}, []

        def on_blobs(msg):
            with lock:
                blobs[msg.header.stamp] = msg

        def on_diagnostics(msg):
            with lock:
                statuses.extend((msg.header.stamp, s) for s in msg.status if s.name.endswith('tracker'))

        rospy.Subscriber('/%s/blobs' % CAMERA, BlobArray, on_blobs, queue_size=20)
        rospy.Subscriber('/diagnostics', DiagnosticArray, on_diagnostics, queue_size=20)
        pub = rospy.Publisher('/%s/image_raw' % CAMERA, Image, queue_size=2)
        pipeline = subprocess.Popen(['roslaunch', 'rle_vision', 'pipeline.launch', 'camera:=' + CAMERA,
                                     'colors_file:=' + self.colors, 'compressed:=false',
                                     'learning:=false'],  # the candidates stay the verifier's own range
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            require(lambda: pub.get_num_connections() > 0, 60 * SLOW, 'the pipeline subscribing to the image')
            found = self.publish_unseen_frames(pub, blobs, lock)
            # The total as reported after the last frame's blobs came back: a report from before
            # (diagnostics come once a second) would miss the last frames' rejections.
            after = rospy.Time.now()
            rejected, = require(lambda: self.rejected_total(statuses, lock, after), 10 * SLOW,
                                'diagnostics counting rejected candidates after the last frame')
        finally:
            os.killpg(pipeline.pid, signal.SIGINT)
            pipeline.wait(timeout=30 * SLOW)
        rospy.loginfo('balls kept on %d of %d unseen frames, %d other ball blobs; %d candidates rejected',
                      found['balls'], TEST_FRAMES, found['others'], rejected)
        self.assertGreaterEqual(found['balls'], TEST_FRAMES - 1)
        self.assertLessEqual(found['others'], 1)
        self.assertEqual(found['goals'], TEST_FRAMES)
        self.assertGreaterEqual(rejected, TEST_FRAMES)  # a bar and a patch a frame, nearly all dropped

    def publish_unseen_frames(self, pub, blobs, lock):
        found = {'balls': 0, 'others': 0, 'goals': 0}
        for i in range(TEST_FRAMES):
            path = os.path.join(self.dir, 'unseen', 'frame_%d' % i)
            bgr = cv2.imread(path + '.png')
            cv2.rectangle(bgr, (2, 2), (33, 17), (200, 40, 30), cv2.FILLED)  # a blue goal above every shape, no verifier
            box = ball_box(path + '.txt', bgr.shape[1], bgr.shape[0])
            stamp = rospy.Time.now()
            # Published until its blobs come back: the first frames may arrive before the subscription.
            msg = wait_for(lambda: pub.publish(image_msg(bgr, stamp)) or blobs.get(stamp), 20 * SLOW, period_s=0.5)
            self.assertTrue(msg, 'no blobs for unseen frame %d' % i)
            for b in msg.blobs:
                if b.color == 'goal':
                    self.assertTrue(math.isnan(b.score), 'a class without a verifier has no score: %s' % b)
                    found['goals'] += 1
                    continue
                self.assertEqual(b.color, 'ball')
                self.assertGreaterEqual(b.score, 0.5)
                self.assertLessEqual(b.score, 1.0)
                on_ball = box[0] <= b.cx <= box[2] and box[1] <= b.cy <= box[3]
                found['balls' if on_ball else 'others'] += 1
        return found

    @staticmethod
    def rejected_total(statuses, lock, after):
        """[the rejected total] of the newest tracker report stamped after `after`; None before one."""
        with lock:
            for stamp, status in reversed(statuses):
                if stamp <= after:
                    return None
                for kv in status.values:
                    if kv.key == 'verifier candidates rejected under min_score (total)':
                        return [int(kv.value)]
        return None


if __name__ == '__main__':
    rospy.init_node('test_verifier_pipeline')
    rostest.rosrun('rle_vision', 'test_verifier_pipeline', VerifierPipelineTest)
