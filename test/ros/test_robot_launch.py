#!/usr/bin/env python3
"""rostest: robot.launch with camera:=head_camera on frames published on
/head_camera/color/image_raw (robot_launch.test). On the same frames as the simulator's ground
truth: every box in full view is a blob of its colour near its true centroid, lines come out of
the landmark node, and obstacles are placed near the boxes' true footprints (tf mode, the
camera_info of color/camera_info). The rviz config robot.launch wrote names the head_camera
topics and no /camera/ one."""
import math
import os
import sys
import threading
import unittest

import rospy
import rostest
from rle_vision.msg import BlobArray, LineArray, ObstacleArray, SceneTruth

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from waiting import SLOW, require  # noqa: E402

FRAMES = 10  # frames with truth, blobs, lines and obstacles of the same stamp


class RobotLaunchTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.truth, self.blobs, self.lines, self.obstacles = {}, {}, {}, {}
        for topic, msg_type, store in (('/head_camera/color/ground_truth/scene', SceneTruth, self.truth),
                                       ('/head_camera/blobs', BlobArray, self.blobs),
                                       ('/head_camera/lines', LineArray, self.lines),
                                       ('/head_camera/obstacles', ObstacleArray, self.obstacles)):
            rospy.Subscriber(topic, msg_type, self.storer(store), queue_size=100)

    def storer(self, store):
        def store_msg(msg):
            with self.lock:
                store[msg.header.stamp] = msg
        return store_msg

    def complete_stamps(self):
        with self.lock:
            return sorted(set(self.truth) & set(self.blobs) & set(self.lines) & set(self.obstacles))

    def test_blobs_lines_and_obstacles_on_the_head_camera(self):
        require(lambda: len(self.complete_stamps()) >= FRAMES, 90 * SLOW,
                '%d frames with blobs, lines and obstacles on /head_camera' % FRAMES)
        boxes = found = placed = lines = 0
        for stamp in self.complete_stamps()[:FRAMES]:
            truth, blobs = self.truth[stamp], self.blobs[stamp].blobs
            lines += len(self.lines[stamp].lines) > 0
            for box in truth.objects:
                in_full_view = box.area > 400 and box.pieces == 1 and not box.touches_same_color
                if not in_full_view:
                    continue
                boxes += 1
                found += any(b.color == box.color and math.hypot(b.cx - box.cx, b.cy - box.cy) < 5 for b in blobs)
                placed += any(o.color == box.color and
                              math.hypot(o.position.x - box.position.x, o.position.y - box.position.y) <
                              0.15 * math.hypot(box.position.x, box.position.y) + 0.1
                              for o in self.obstacles[stamp].obstacles)
        rospy.loginfo('%d boxes in full view: %d found as blobs, %d placed as obstacles; lines on %d of %d frames',
                      boxes, found, placed, lines, FRAMES)
        self.assertGreaterEqual(boxes, FRAMES)
        self.assertGreaterEqual(found, 0.95 * boxes)
        self.assertGreaterEqual(placed, 0.8 * boxes)
        self.assertEqual(lines, FRAMES)

    def test_the_rviz_config_follows_the_camera(self):
        path = rospy.get_param('~rviz_config')
        require(lambda: os.path.isfile(path), 30 * SLOW, 'robot.launch writing ' + path)
        text = open(path).read()
        os.remove(path)  # the next run must write its own
        self.assertIn('Image Topic: /head_camera/tracker/debug_image', text)
        self.assertIn('Marker Topic: /head_camera/ground_projector/markers', text)
        self.assertNotIn(': /camera/', text)


if __name__ == '__main__':
    rospy.init_node('test_robot_launch')
    rostest.rosrun('rle_vision', 'test_robot_launch', RobotLaunchTest)
