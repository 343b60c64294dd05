#!/usr/bin/env python3
"""Makes the files the README's commands name, for make test-readme: three camera frames with
a ball and YOLO labels (/tmp/rle_vision_frames), and bags recorded the ways robots record a
camera: raw (/tmp/run.bag, /tmp/rect.bag), JPEG-compressed (/tmp/head.bag) and Bayer
(/tmp/bayer.bag); a colour file (/tmp/my_colors.yaml). The frames are synthetic: a sky over textured ground, a red box of the
shipped colour classes, an orange ball."""
import os

import cv2
import numpy as np
import rosbag
import rospy
from sensor_msgs.msg import CameraInfo, CompressedImage, Image

FRAMES_DIR = '/tmp/rle_vision_frames'
BALL_BOX = (300, 330, 340, 370)  # x0, y0, x1, y1 in frame_0001 (moves 20 px right per frame)


def frame(i):
    rng = np.random.default_rng(i)
    image = np.full((480, 640, 3), (225, 185, 140), np.uint8)
    image[200 + 3 * i:] = np.clip(rng.normal((70, 120, 90), 10, (280 - 3 * i, 640, 3)), 0, 255).astype(np.uint8)
    image[380:440, 80 + 20 * i:160 + 20 * i] = (40, 40, 220)  # red, as config/colors.yaml has it
    x0, y0, x1, y1 = BALL_BOX
    cv2.circle(image, ((x0 + x1) // 2 + 20 * i, (y0 + y1) // 2), (x1 - x0) // 2, (0, 120, 250), -1, cv2.LINE_AA)
    return image


def write_frames():
    os.makedirs(FRAMES_DIR, exist_ok=True)
    for i in range(3):
        name = os.path.join(FRAMES_DIR, 'frame_%04d' % (i + 1))
        cv2.imwrite(name + '.png', frame(i))
        x0, y0, x1, y1 = BALL_BOX
        with open(name + '.txt', 'w') as f:  # YOLO: class cx cy w h, normalised
            f.write('0 %.6f %.6f %.6f %.6f\n' % (((x0 + x1) / 2 + 20 * i) / 640, (y0 + y1) / 2 / 480,
                                                   (x1 - x0) / 640, (y1 - y0) / 480))


def bayer_rggb(bgr):
    mosaic = np.empty(bgr.shape[:2], np.uint8)
    mosaic[0::2, 0::2], mosaic[0::2, 1::2] = bgr[0::2, 0::2, 2], bgr[0::2, 1::2, 1]
    mosaic[1::2, 0::2], mosaic[1::2, 1::2] = bgr[1::2, 0::2, 1], bgr[1::2, 1::2, 0]
    return mosaic


def image_msg(kind, bgr):
    if kind == 'jpeg':
        return CompressedImage(format='bgr8; jpeg compressed bgr8', data=cv2.imencode('.jpg', bgr)[1].tobytes())
    if kind == 'bayer':
        mosaic = bayer_rggb(bgr)
        return Image(height=480, width=640, encoding='bayer_rggb8', step=640, data=mosaic.tobytes())
    return Image(height=480, width=640, encoding='bgr8', step=640 * 3, data=bgr.tobytes())


def write_bag(path, camera, image_topic, kind, frames=30):
    with rosbag.Bag(path, 'w') as bag:
        for i in range(frames):
            stamp = rospy.Time(100) + rospy.Duration(i / 30.0)
            msg = image_msg(kind, frame(i % 3))
            msg.header.stamp, msg.header.frame_id = stamp, 'camera_optical_frame'
            info = CameraInfo(height=480, width=640, distortion_model='plumb_bob', D=[0.0] * 5,
                              K=[500.0, 0, 320, 0, 500.0, 240, 0, 0, 1], P=[500.0, 0, 320, 0, 0, 500.0, 240, 0, 0, 0, 1, 0])
            info.header = msg.header
            bag.write('/%s/%s' % (camera, image_topic), msg, stamp)
            bag.write('/%s/camera_info' % camera, info, stamp)


def write_colours():
    """/tmp/my_colors.yaml, the colour file the README's robot command names: the shipped one."""
    if not os.path.exists('/tmp/my_colors.yaml'):
        root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
        with open(os.path.join(root, 'config', 'colors.yaml')) as src, open('/tmp/my_colors.yaml', 'w') as dst:
            dst.write(src.read())


def main():
    write_colours()
    write_frames()
    write_bag('/tmp/run.bag', 'camera', 'image_raw', 'raw')
    write_bag('/tmp/rect.bag', 'head_cam', 'image_rect_color', 'raw')
    write_bag('/tmp/head.bag', 'head_cam', 'image_raw/compressed', 'jpeg')
    write_bag('/tmp/bayer.bag', 'head_cam', 'image_raw', 'bayer')
    print('[readme] made %s/frame_000{1,2,3}.png (+ YOLO labels) and /tmp/{run,rect,head,bayer}.bag' % FRAMES_DIR)


if __name__ == '__main__':
    main()
