"""X window dumps (xwd -root) to RGB, PNG writing, and colour counting: pure Python, for the
rviz screenshot test and `make screenshot`."""
import struct
import zlib


def read_xwd(data):
    """(width, height, rgb bytes) of a 24/32-bit ZPixmap X window dump."""
    fields = struct.unpack('>25I', data[:100])
    header_size, version, pixmap_format, depth, width, height = fields[:6]
    byte_order, bits_per_pixel, bytes_per_line = fields[7], fields[11], fields[12]
    red_mask, green_mask, blue_mask = fields[14:17]
    ncolors = fields[19]
    if version != 7 or pixmap_format != 2 or bits_per_pixel not in (24, 32):
        raise ValueError('unsupported xwd: version %d, format %d, %d bits per pixel' % (version, pixmap_format, bits_per_pixel))
    offset = header_size + 12 * ncolors
    step = bits_per_pixel // 8
    shifts = [(mask, (mask & -mask).bit_length() - 1) for mask in (red_mask, green_mask, blue_mask)]
    rgb = bytearray(width * height * 3)
    endian = 'little' if byte_order == 0 else 'big'
    for y in range(height):
        row = data[offset + y * bytes_per_line: offset + y * bytes_per_line + width * step]
        for x in range(width):
            pixel = int.from_bytes(row[x * step:(x + 1) * step], endian)
            i = (y * width + x) * 3
            rgb[i], rgb[i + 1], rgb[i + 2] = [(pixel & mask) >> shift for mask, shift in shifts]
    return width, height, bytes(rgb)


def write_png(path, width, height, rgb, scale=1):
    """An 8-bit RGB PNG; `scale` > 1 averages scale x scale blocks (a small file for docs)."""
    if scale > 1:
        w, h = width // scale, height // scale
        out = bytearray(w * h * 3)
        n = scale * scale
        for y in range(h):
            for x in range(w):
                for c in range(3):
                    total = sum(rgb[((y * scale + dy) * width + x * scale + dx) * 3 + c]
                                for dy in range(scale) for dx in range(scale))
                    out[(y * w + x) * 3 + c] = (total + n // 2) // n
        width, height, rgb = w, h, bytes(out)
    raw = b''.join(b'\x00' + rgb[y * width * 3:(y + 1) * width * 3] for y in range(height))

    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def count_near(width, height, rgb, colour, tolerance, region=None):
    """Pixels within `tolerance` (every channel) of `colour` inside region (x0, y0, x1, y1)."""
    x0, y0, x1, y1 = region or (0, 0, width, height)
    r, g, b = colour
    count = 0
    for y in range(y0, y1):
        row = rgb[(y * width + x0) * 3:(y * width + x1) * 3]
        for i in range(0, len(row), 3):
            if abs(row[i] - r) <= tolerance and abs(row[i + 1] - g) <= tolerance and abs(row[i + 2] - b) <= tolerance:
                count += 1
    return count
