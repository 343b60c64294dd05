"""Pure-Python synthetic images for the rostests (no numpy or cv_bridge needed)."""
import math

from sensor_msgs.msg import Image


class BgrImage:
    def __init__(self, width, height, bgr):
        self.width, self.height = width, height
        self.data = bytearray(bytes(bgr) * (width * height))

    def fill_rect(self, x0, y0, x1, y1, bgr):
        """Pixels x0 <= x < x1, y0 <= y < y1."""
        row = bytes(bgr) * (x1 - x0)
        for y in range(y0, y1):
            start = (y * self.width + x0) * 3
            self.data[start:start + len(row)] = row

    def fill_below_line(self, angle_deg, y_at_centre, bgr):
        """Pixels below the line through (width / 2, y_at_centre) at angle_deg (image axes)."""
        slope = math.tan(math.radians(angle_deg))
        for y in range(self.height):
            for x in range(self.width):
                if y > y_at_centre + slope * (x - self.width / 2.0):
                    start = (y * self.width + x) * 3
                    self.data[start:start + 3] = bytes(bgr)

    def add_ground_texture(self, angle_deg, y_at_centre, amplitude, seed=1):
        """Grey grain of +-amplitude on every pixel below the line fill_below_line draws: real
        ground is textured and the sky is smooth, which the horizon detector weighs."""
        slope = math.tan(math.radians(angle_deg))
        state = seed
        for y in range(self.height):
            for x in range(self.width):
                state = (state * 1103515245 + 12345) % 2147483648  # a fixed LCG: the same grain every run
                if y > y_at_centre + slope * (x - self.width / 2.0):
                    delta = (state >> 16) % (2 * amplitude + 1) - amplitude
                    start = (y * self.width + x) * 3
                    for i in range(start, start + 3):
                        self.data[i] = max(0, min(255, self.data[i] + delta))

    def add_pattern_noise(self, amplitude):
        """A fixed +-amplitude pattern (keeps colour statistics from being degenerate)."""
        for i in range(len(self.data)):
            delta = ((i * 7919) % 5 - 2) * amplitude // 2
            self.data[i] = max(0, min(255, self.data[i] + delta))

    def scaled(self, gain):
        """A copy under light gain `gain`: every channel of every pixel times gain."""
        copy = BgrImage(self.width, self.height, (0, 0, 0))
        copy.data = bytearray(bytes(self.data).translate(bytes(min(255, int(i * gain + 0.5)) for i in range(256))))
        return copy

    def ppm(self):
        """Binary PPM bytes (RGB) of the image, for the command-line tools."""
        rgb = bytearray(len(self.data))
        rgb[0::3], rgb[1::3], rgb[2::3] = self.data[2::3], self.data[1::3], self.data[0::3]
        return b'P6 %d %d 255\n' % (self.width, self.height) + bytes(rgb)

    def msg(self, stamp, frame_id='camera_optical_frame'):
        m = Image()
        m.header.stamp = stamp
        m.header.frame_id = frame_id
        m.width, m.height = self.width, self.height
        m.encoding = 'bgr8'
        m.step = self.width * 3
        m.data = bytes(self.data)
        return m


def bgr_from_yuv(y, u, v):
    """OpenCV's COLOR_YUV2BGR of one colour (the inverse of COLOR_BGR2YUV, the tracker's YUV:
    U = 0.492 (B - Y) + 128, V = 0.877 (R - Y) + 128)."""
    r = y + 1.140 * (v - 128)
    g = y - 0.395 * (u - 128) - 0.581 * (v - 128)
    b = y + 2.032 * (u - 128)
    return tuple(int(round(max(0, min(255, c)))) for c in (b, g, r))
