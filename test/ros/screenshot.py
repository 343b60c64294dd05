"""X window dumps (xwd -root) to RGB arrays, PNG writing, and colour counting with numpy, for
the rviz screenshot test and `make screenshot`. Counting a 1024x768 dump takes milliseconds, so
a test can retake the screenshot every second until what it checks is drawn."""
import struct
import zlib

import numpy as np


def read_xwd(data):
    """The rgb array (height x width x 3, uint8) of a 24/32-bit ZPixmap X window dump."""
    fields = struct.unpack('>25I', data[:100])
    header_size, version, pixmap_format, depth, width, height = fields[:6]
    byte_order, bits_per_pixel, bytes_per_line = fields[7], fields[11], fields[12]
    red_mask, green_mask, blue_mask = fields[14:17]
    ncolors = fields[19]
    if version != 7 or pixmap_format != 2 or bits_per_pixel not in (24, 32):
        raise ValueError('unsupported xwd: version %d, format %d, %d bits per pixel' % (version, pixmap_format, bits_per_pixel))
    offset = header_size + 12 * ncolors
    step = bits_per_pixel // 8
    rows = np.frombuffer(data, np.uint8, count=bytes_per_line * height, offset=offset).reshape(height, bytes_per_line)
    pixels = rows[:, :width * step].reshape(height, width, step).astype(np.uint32)
    order = range(step) if byte_order == 0 else reversed(range(step))  # LSB first or MSB first
    value = np.zeros((height, width), np.uint32)
    for shift, byte in enumerate(order):
        value |= pixels[:, :, byte] << np.uint32(8 * shift)
    channels = [((value & np.uint32(mask)) >> np.uint32((mask & -mask).bit_length() - 1)).astype(np.uint8)
                for mask in (red_mask, green_mask, blue_mask)]
    return np.dstack(channels)


def write_png(path, rgb, scale=1):
    """An 8-bit RGB PNG of an rgb array; `scale` > 1 averages scale x scale blocks (a small
    file for docs)."""
    if scale > 1:
        h, w = rgb.shape[0] // scale, rgb.shape[1] // scale
        blocks = rgb[:h * scale, :w * scale].reshape(h, scale, w, scale, 3).astype(np.uint32)
        n = scale * scale
        rgb = ((blocks.sum(axis=(1, 3)) + n // 2) // n).astype(np.uint8)
    height, width = rgb.shape[:2]
    raw = b''.join(b'\x00' + rgb[y].tobytes() for y in range(height))

    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def crop(rgb, region):
    x0, y0, x1, y1 = region
    return rgb[y0:y1, x0:x1].astype(np.int16)


def count_near(rgb, colour, tolerance, region):
    """Pixels within `tolerance` (every channel) of `colour` inside region (x0, y0, x1, y1)."""
    difference = np.abs(crop(rgb, region) - np.array(colour, np.int16))
    return int(np.count_nonzero(np.all(difference <= tolerance, axis=2)))


def count_red_lit(rgb, region):
    """Pixels of a red-lit surface (red > 120, green and blue < 60) inside region."""
    part = crop(rgb, region)
    return int(np.count_nonzero((part[:, :, 0] > 120) & (part[:, :, 1] < 60) & (part[:, :, 2] < 60)))
