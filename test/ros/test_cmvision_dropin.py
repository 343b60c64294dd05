#!/usr/bin/env python3
"""rostest: cmvision.launch is a drop-in for cmvision. A subscriber typed exactly as cmvision's
cmvision/Blobs (generated here from cmvision's message definition; the cmvision package itself
is not needed) receives the blobs on /blobs, and they agree with rle_vision's own BlobArray."""
import sys
import threading
import unittest

import genpy.dynamic
import rospy
import rostest
from rle_vision.msg import BlobArray, CmvisionBlobs

sys.path.insert(0, __file__.rsplit('/', 1)[0])
from truth_matching import store_by_stamp  # noqa: E402
from waiting import SLOW, wait_for  # noqa: E402

# cmvision's msg/Blobs.msg and msg/Blob.msg, in the layout of a message's full text.
CMVISION_BLOBS = """Header header
uint32 image_width
uint32 image_height
uint32 blob_count
Blob[] blobs

================================================================================
MSG: cmvision/Blob
string name
uint32 red
uint32 green
uint32 blue
uint32 area
uint32 x
uint32 y
uint32 left
uint32 right
uint32 top
uint32 bottom

================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
"""
DISPLAY_RGB = {'red': (255, 40, 40), 'yellow': (255, 230, 0), 'blue': (40, 80, 255), 'magenta': (230, 40, 220)}


class CmvisionDropInTest(unittest.TestCase):
    def test_cmvision_subscribers_get_the_blobs(self):
        cmvision_blobs_type = genpy.dynamic.generate_dynamic('cmvision/Blobs', CMVISION_BLOBS)['cmvision/Blobs']
        self.assertEqual(cmvision_blobs_type._md5sum, CmvisionBlobs._md5sum)
        lock = threading.Lock()
        cm, native = {}, {}
        rospy.Subscriber('/blobs', cmvision_blobs_type, store_by_stamp(lock, cm), queue_size=50)
        rospy.Subscriber('/rle_blobs', BlobArray, store_by_stamp(lock, native), queue_size=50)
        def enough():
            with lock:
                return len(set(cm) & set(native)) >= 30
        wait_for(enough, 30 * SLOW)
        with lock:
            pairs = [(cm[s], native[s]) for s in sorted(set(cm) & set(native))]
        self.assertGreaterEqual(len(pairs), 30, 'cmvision-typed subscriber got %d messages' % len(cm))
        for c, n in pairs:
            self.assertEqual(c.blob_count, len(c.blobs))
            self.assertEqual(len(c.blobs), len(n.blobs))
            self.assertEqual((c.image_width, c.image_height), (640, 480))
            # cmvision's order: by class (colors.txt order), then by area, largest first.
            order = [(list(DISPLAY_RGB).index(b.name), -b.area) for b in c.blobs]
            self.assertEqual(order, sorted(order))
            by_box = {(b.left, b.top, b.right, b.bottom): b for b in n.blobs}
            for b in c.blobs:
                own = by_box[(b.left, b.top, b.right - 1, b.bottom)]  # cmvision: right is one past
                self.assertEqual((b.name, b.area), (own.color, own.area))
                self.assertEqual((b.red, b.green, b.blue), DISPLAY_RGB[b.name])
                self.assertEqual((b.x, b.y), (int(round(own.cx + 0.5)), int(round(own.cy + 0.5))))
        rospy.loginfo('cmvision drop-in: %d messages, %d blobs in the last', len(pairs), len(pairs[-1][0].blobs))


if __name__ == '__main__':
    rospy.init_node('test_cmvision_dropin')
    rostest.rosrun('rle_vision', 'test_cmvision_dropin', CmvisionDropInTest)
