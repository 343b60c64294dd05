#!/usr/bin/env python3
"""rostest: bags recorded the way robots record cameras (JPEG CompressedImage on
.../image_raw/compressed, raw Bayer on .../image_raw), played with play.launch: every frame
gives blobs, lines and a horizon message with the bag's stamp, and the red marker painted into
each frame is found where it was painted (so decoding and demosaicing keep the colours). The
bags hold no tf: the ground projector must say so while the bag plays, about a second after
the first frame, not only once its queue of waiting blobs (30) is full: before the blobs of
the bag's last frame (the 12th)."""
import glob
import os
import signal
import subprocess
import sys
import threading
import unittest

import cv2
import numpy as np
import rosbag
import rospkg
import rospy
import rostest
from rle_vision.msg import BlobArray, Horizon, LineArray, ObstacleArray
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import CameraInfo, CompressedImage, Image
from std_srvs.srv import SetBool

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from truth_matching import wait_until_wired  # noqa: E402
from waiting import SLOW, wait_for  # noqa: E402

FRAMES = 12
MARKER_PX = 40
MARKER_BGR = (40, 40, 220)  # inside config/colors.yaml's red class
CAMERA_TOPIC = '/robot/front_cam'
TOPICS = {'blobs': BlobArray, 'lines': LineArray, 'horizon': Horizon}


def source_frames(frames_dir):
    """Real frames when the data set is there, otherwise a synthetic sky over textured ground."""
    files = sorted(glob.glob(os.path.join(frames_dir, '*.jpg')))
    if len(files) >= FRAMES:
        step = len(files) // FRAMES
        return [cv2.resize(cv2.imread(f), (480, 480)) for f in files[::step][:FRAMES]], 'real'
    rng = np.random.default_rng(1)
    frames = []
    for i in range(FRAMES):
        image = np.full((480, 480, 3), (230, 190, 150), np.uint8)
        horizon = 200 + 4 * i
        image[horizon:] = np.clip(rng.normal((60, 110, 80), 12, (480 - horizon, 480, 3)), 0, 255).astype(np.uint8)
        frames.append(image)
    return frames, 'synthetic'


def marker_centre(i):
    return 60 + 25 * i + MARKER_PX / 2.0 - 0.5, 400 + MARKER_PX / 2.0 - 0.5


def with_marker(image, i):
    out = image.copy()
    x0 = 60 + 25 * i
    out[400:400 + MARKER_PX, x0:x0 + MARKER_PX] = MARKER_BGR
    return out


def bayer_rggb(bgr):
    mosaic = np.empty(bgr.shape[:2], np.uint8)
    mosaic[0::2, 0::2] = bgr[0::2, 0::2, 2]
    mosaic[0::2, 1::2] = bgr[0::2, 1::2, 1]
    mosaic[1::2, 0::2] = bgr[1::2, 0::2, 1]
    mosaic[1::2, 1::2] = bgr[1::2, 1::2, 0]
    return mosaic


def write_bag(path, frames, kind):
    """Frames at 10 Hz from t = 100 s, with a camera_info each."""
    stamps = []
    with rosbag.Bag(path, 'w') as bag:
        for i, frame in enumerate(frames):
            stamp = rospy.Time(100) + rospy.Duration(0.1 * i)
            stamps.append(stamp)
            info = CameraInfo(height=frame.shape[0], width=frame.shape[1], distortion_model='plumb_bob', D=[0.0] * 5,
                              K=[400.0, 0, 240, 0, 400.0, 240, 0, 0, 1])
            info.header.stamp, info.header.frame_id = stamp, 'front_cam'
            if kind == 'jpeg':
                msg = CompressedImage(format='bgr8; jpeg compressed bgr8',
                                      data=cv2.imencode('.jpg', frame, [cv2.IMWRITE_JPEG_QUALITY, 90])[1].tobytes())
                topic = CAMERA_TOPIC + '/image_raw/compressed'
            else:
                mosaic = bayer_rggb(frame)
                msg = Image(height=mosaic.shape[0], width=mosaic.shape[1], encoding='bayer_rggb8', step=mosaic.shape[1],
                            data=mosaic.tobytes())
                topic = CAMERA_TOPIC + '/image_raw'
            msg.header.stamp, msg.header.frame_id = stamp, 'front_cam'
            bag.write(topic, msg, stamp)
            bag.write(CAMERA_TOPIC + '/camera_info', info, stamp)
    return stamps


class RobotBagsTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.outputs = {name: {} for name in TOPICS}
        for name, msg_type in TOPICS.items():
            rospy.Subscriber('/replay/' + name, msg_type, self.store(name), queue_size=100)
        self.blobs_before_warning = None  # blob messages received when the no-transform warning came
        rospy.Subscriber('/replay/obstacles', ObstacleArray, lambda msg: None)  # the ground projector works only for a reader
        rospy.Subscriber('/rosout', Log, self.log_cb, queue_size=100)
        self.frames, self.source = source_frames(rospy.get_param('~frames_dir'))
        self.frames = [with_marker(f, i) for i, f in enumerate(self.frames)]
        rospy.loginfo('%d %s frames', len(self.frames), self.source)

    def store(self, name):
        def callback(msg):
            with self.lock:
                self.outputs[name][msg.header.stamp] = msg
        return callback

    def log_cb(self, msg):
        with self.lock:
            if msg.level == Log.WARN and 'no transform from' in msg.msg and self.blobs_before_warning is None:
                self.blobs_before_warning = len(self.outputs['blobs'])

    def play(self, kind, args, inputs):
        path = os.path.join(rospy.get_param('~bag_dir'), 'rle_vision_robot_%s.bag' % kind)
        stamps = write_bag(path, self.frames, kind)
        with self.lock:
            self.blobs_before_warning = None
        play = subprocess.Popen(['roslaunch', 'rle_vision', 'play.launch', 'bag:=' + path, 'camera:=replay',
                                 'camera_info_topic:=' + CAMERA_TOPIC + '/camera_info', 'learning:=false',
                                 'start_delay_s:=0', 'paused:=true', 'rate:=0.5'] + args,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            self.assertTrue(wait_until_wired(inputs, 60 * SLOW), 'the %s replay never connected %s' % (kind, inputs))
            rospy.ServiceProxy('/play/pause_playback', SetBool)(False)

            def every_output():
                with self.lock:
                    return all(set(stamps) <= set(self.outputs[name]) for name in TOPICS)
            wait_for(every_output, 60 * SLOW, period_s=0.2)
        finally:
            os.killpg(play.pid, signal.SIGINT)
            play.wait(timeout=30 * SLOW)
        with self.lock:
            for name in TOPICS:
                missing = [s.to_sec() for s in stamps if s not in self.outputs[name]]
                self.assertEqual(missing, [], '%s (%s bag): no %s for these stamps' % (self.source, kind, name))
            for i, stamp in enumerate(stamps):
                cx, cy = marker_centre(i)
                red = [b for b in self.outputs['blobs'][stamp].blobs if b.color == 'red']
                near = [b for b in red if abs(b.cx - cx) <= 2.0 and abs(b.cy - cy) <= 2.0 and
                        0.8 * MARKER_PX ** 2 <= b.area <= 1.2 * MARKER_PX ** 2]
                self.assertTrue(near, '%s bag, frame %d: no red blob at (%.1f, %.1f), red blobs: %s' %
                                (kind, i, cx, cy, [(b.cx, b.cy, b.area) for b in red]))
            for name in TOPICS:
                self.outputs[name].clear()
            return self.blobs_before_warning

    def test_jpeg_compressed_bag(self):
        # No image_topic: play.launch finds the bag's only camera, and that it is compressed.
        blobs_before_warning = self.play(
            'jpeg', [],
            ['/replay/image_raw/compressed', '/replay/image_raw', '/replay/edges', '/replay/blobs'])
        # The bag plays at 5 frames per second (rate 0.5): said after the 1-s wait (checked every
        # 0.25 s), some 5-7 frames in, long before the 30-blob queue could be full.
        self.assertIsNotNone(blobs_before_warning, 'the bag has no tf, and nobody said so while it played')
        self.assertLess(blobs_before_warning, FRAMES, 'no-transform warning after the blobs of all %d frames' % FRAMES)
        rospy.loginfo('no-transform warning after the blobs of %d frames', blobs_before_warning)

    def test_bayer_bag(self):
        self.play('bayer', ['image_topic:=' + CAMERA_TOPIC + '/image_raw', 'debayer:=true'],
                  ['/replay/image_raw', '/replay/image_color', '/replay/edges'])

    def test_a_topic_missing_from_the_bag_is_named_with_the_fix(self):
        path = os.path.join(rospy.get_param('~bag_dir'), 'rle_vision_robot_missing.bag')
        write_bag(path, self.frames[:2], 'jpeg')
        player = os.path.join(rospkg.RosPack().get_path('rle_vision'), 'scripts', 'play_bag')
        run = subprocess.run([player, '--bag', path, '--camera', 'replay', '--image-topic', CAMERA_TOPIC + '/image_raw',
                              '--', '--clock'], capture_output=True, text=True, timeout=60 * SLOW)
        self.assertEqual(run.returncode, 2, run.stdout + run.stderr)
        self.assertIn(CAMERA_TOPIC + '/image_raw/compressed (sensor_msgs/CompressedImage)', run.stderr)
        self.assertIn('image_topic:=', run.stderr)

    def test_compressed_frames_on_the_raw_topic_are_reported_with_the_fix(self):
        errors = []
        rospy.Subscriber('/rosout', Log, lambda m: errors.append(m.msg) if m.level == Log.ERROR else None)
        pub = rospy.Publisher('/wrong/image_raw', CompressedImage, queue_size=1)
        pipeline = subprocess.Popen(['roslaunch', 'rle_vision', 'pipeline.launch', 'camera:=wrong', 'compressed:=false'],
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        try:
            wanted = '/wrong/image_raw carries sensor_msgs/CompressedImage'
            wait_for(lambda: any(wanted in e for e in errors), 60 * SLOW, period_s=0.2)
        finally:
            os.killpg(pipeline.pid, signal.SIGINT)
            pipeline.wait(timeout=30 * SLOW)
            pub.unregister()
        found = [e for e in errors if wanted in e]
        self.assertTrue(found, 'no error naming the misrouted topic; errors: %s' % errors)
        self.assertIn('/wrong/image_raw/compressed', found[0])


if __name__ == '__main__':
    rospy.init_node('test_robot_bags')
    rostest.rosrun('rle_vision', 'test_robot_bags', RobotBagsTest)
