#!/usr/bin/env python3
"""rostest: rviz with config/rle_vision.rviz on the running demo graph, under Xvfb. A real GUI
check: the screenshot must show the two image panels with the camera image (sky pixels) and
the overlay in the classes' display colours (box outlines and colour swatches, colours the
scene itself never has), and the obstacles as red cylinders in the 3D view. Writes the
screenshot to $ROS_HOME/rviz_screenshot.png, and a half-size copy to $RLE_VISION_SCREENSHOT
when that is set (`make screenshot` uses it for the README)."""
import os
import shutil
import subprocess
import sys
import time
import unittest

import rospkg
import rospy
import rostest

sys.path.insert(0, __file__.rsplit('/', 1)[0])
import screenshot  # noqa: E402

WIDTH, HEIGHT = 1024, 768
IMAGE_COLUMN = (0, 60, 330, 740)   # the docked image panels (left)
VIEW_3D = (350, 60, 1010, 740)
DISPLAY_RGB = {'red': (255, 40, 40), 'yellow': (255, 230, 0), 'blue': (40, 80, 255), 'magenta': (230, 40, 220)}
SKY = (170, 205, 235)


def free_display():
    for n in range(90, 200):
        if not os.path.exists('/tmp/.X%d-lock' % n) and not os.path.exists('/tmp/.X11-unix/X%d' % n):
            return ':%d' % n
    raise RuntimeError('no free X display number')


class RvizScreenshotTest(unittest.TestCase):
    def test_rviz_shows_the_overlay_and_the_obstacles(self):
        config = os.path.join(rospkg.RosPack().get_path('rle_vision'), 'config', 'rle_vision.rviz')
        display = free_display()
        xvfb = subprocess.Popen([shutil.which('Xvfb'), display, '-screen', '0', '%dx%dx24' % (WIDTH, HEIGHT), '-nolisten', 'tcp'],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        env = dict(os.environ, DISPLAY=display)
        rviz = None
        try:
            time.sleep(1.0)
            rviz = subprocess.Popen([shutil.which('rviz'), '-d', config], env=env,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            found, counts = False, {}
            deadline = time.time() + 60
            while time.time() < deadline and not found:
                time.sleep(3.0)
                dump = subprocess.run(['xwd', '-root', '-silent'], env=env, stdout=subprocess.PIPE, check=True).stdout
                width, height, rgb = screenshot.read_xwd(dump)
                counts = {name: screenshot.count_near(width, height, rgb, colour, 6, IMAGE_COLUMN)
                          for name, colour in DISPLAY_RGB.items()}
                counts['sky'] = screenshot.count_near(width, height, rgb, SKY, 12, IMAGE_COLUMN)
                counts['leaked into 3D view'] = sum(screenshot.count_near(width, height, rgb, c, 6, VIEW_3D)
                                                    for c in DISPLAY_RGB.values())
                found = all(counts[name] >= 50 for name in DISPLAY_RGB) and counts['sky'] >= 5000
            # Red-lit cylinder pixels in the 3D view: the obstacles' markers.
            x0, y0, x1, y1 = VIEW_3D
            counts['red obstacles'] = sum(1 for y in range(y0, y1) for x in range(x0, x1)
                                          if rgb[(y * width + x) * 3] > 120 and rgb[(y * width + x) * 3 + 1] < 60
                                          and rgb[(y * width + x) * 3 + 2] < 60)
        finally:
            if rviz:
                rviz.terminate()
                rviz.wait(timeout=20)
            xvfb.terminate()
            xvfb.wait(timeout=20)
        ros_home = os.environ.get('ROS_HOME', os.path.expanduser('~/.ros'))
        full = os.path.join(ros_home, 'rviz_screenshot.png')
        screenshot.write_png(full, width, height, rgb)
        if os.environ.get('RLE_VISION_SCREENSHOT'):
            screenshot.write_png(os.environ['RLE_VISION_SCREENSHOT'], width, height, rgb, scale=2)
        rospy.loginfo('rviz screenshot %s: pixels %s', full, counts)
        for name in DISPLAY_RGB:
            self.assertGreaterEqual(counts[name], 50, '%s overlay pixels in the image panels: %s (see %s)' % (name, counts, full))
        self.assertGreaterEqual(counts['sky'], 5000, 'the image panels show no camera image: %s (see %s)' % (counts, full))
        self.assertEqual(counts['leaked into 3D view'], 0)
        self.assertGreaterEqual(counts['red obstacles'], 300, 'no obstacle markers in the 3D view: %s (see %s)' % (counts, full))


if __name__ == '__main__':
    rospy.init_node('test_rviz_screenshot')
    rostest.rosrun('rle_vision', 'test_rviz_screenshot', RvizScreenshotTest)
