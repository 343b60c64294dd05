#!/usr/bin/env python3
"""How far can one colour box go? The best single box per colour space for the scored folders'
OWN labels, with the ball score of `make eval` (a blob of >= 20 px whose centroid lies in a
labelled ball box finds that ball; blob precision is the share of such blobs on a ball).

  ball_box_bound.py --calibrate DIR [--label-class N] [--json OUT] DIR...

The box is fitted to the very frames it is scored on, so it is a yardstick, not a method: a
range calibrated on other frames is not expected to beat it. The search is local, so what it
finds is a floor under the best box, not a proof that none does better. The search is
coordinate ascent on min(recall, precision) over the six bounds (moves of 1 to 16 levels),
started from rle_vision_calibrate's class and statistics for DIR in that space and from the
statistics' mean +- 1, 2 and 4 sigma. A bound below 90 means that no box this search finds
reaches 90% recall and 90% precision together. Blob precision counts every piece of a ball cut
into several blobs as on the ball; the JSON also gives the blobs off every ball and the
precision without those extra pieces. Hue ranges that wrap past 0 are not searched. Slow: about
35 minutes for the three spaces on one core."""
import argparse
import datetime
import json
import math
import os
import re
import subprocess
import sys

import cv2
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CALIBRATE = os.path.join(ROOT, '.ws', 'devel', 'lib', 'rle_vision', 'rle_vision_calibrate')
CONVERSIONS = {'YUV': cv2.COLOR_BGR2YUV, 'HSV': cv2.COLOR_BGR2HSV, 'RGB': cv2.COLOR_BGR2RGB}
MIN_BLOB_AREA_PX = 20  # as bench/eval_balls.cpp
STEPS = (-16, -8, -4, -2, -1, 1, 2, 4, 8, 16)


def lround(value):
    """C's lround: halves away from zero (Python's round() takes them to even)."""
    return int(math.copysign(math.floor(abs(value) + 0.5), value))


def yolo_boxes(label_path, label_class, width, height):
    """As readYoloBoxes: [x0, x1) x [y0, y1) in pixels, rounded, at least 1 px, clipped; the
    same lines refused."""
    boxes = []
    if not os.path.exists(label_path):
        return boxes  # YOLO's convention: an image without objects has no label file
    for number, line in enumerate(open(label_path), 1):
        fields = line.split()
        if not fields:
            continue
        where = '%s:%d: ' % (label_path, number)
        if len(fields) != 5 or not re.fullmatch(r'[+-]?\d+', fields[0]):
            sys.exit(where + "expected 'class cx cy w h' (a box label, not a polygon)")
        if int(fields[0]) != label_class:
            continue
        cx, cy, w, h = map(float, fields[1:])
        if not (w > 0 and h > 0):
            sys.exit(where + 'the box is empty (w and h must be > 0)')
        x0, y0 = lround((cx - w / 2) * width), lround((cy - h / 2) * height)
        x1 = max(x0 + 1, lround((cx + w / 2) * width))
        y1 = max(y0 + 1, lround((cy + h / 2) * height))
        box = (max(0, x0), max(0, y0), min(width, x1), min(height, y1))
        if box[0] >= box[2] or box[1] >= box[3]:
            sys.exit(where + 'the box lies outside the image')
        boxes.append(box)
    return boxes


def load(folders, label_class):
    frames = []
    for folder in folders:
        names = sorted(n for n in os.listdir(folder) if os.path.splitext(n)[1].lower() in ('.jpg', '.jpeg', '.png'))
        for path in (os.path.join(folder, n) for n in names):
            bgr = cv2.imread(path, cv2.IMREAD_COLOR)
            if bgr is None:
                sys.exit('%s: cannot read the image' % path)
            boxes = yolo_boxes(os.path.splitext(path)[0] + '.txt', label_class, bgr.shape[1], bgr.shape[0])
            frames.append((bgr, boxes))
    if not frames:
        sys.exit('no images in %s' % ' '.join(folders))
    return frames


def score(frames_in_space, lo, hi):
    balls = found = blobs = on_ball = 0
    for image, boxes in frames_in_space:
        mask = cv2.inRange(image, np.array(lo, np.uint8), np.array(hi, np.uint8))
        n, _, stats, centroids = cv2.connectedComponentsWithStats(mask, connectivity=8)
        kept = [centroids[i] for i in range(1, n) if stats[i][cv2.CC_STAT_AREA] >= MIN_BLOB_AREA_PX]
        inside = [[x0 <= x <= x1 - 1 and y0 <= y <= y1 - 1 for (x0, y0, x1, y1) in boxes] for x, y in kept]
        balls += len(boxes)
        blobs += len(kept)
        found += sum(any(row[b] for row in inside) for b in range(len(boxes)))
        on_ball += sum(any(row) for row in inside)
    recall = 100.0 * found / max(balls, 1)
    precision = 100.0 * on_ball / blobs if blobs else 100.0
    return recall, precision, blobs, found, on_ball


def pieces_not_counted(found, blobs, on_ball):
    """Precision when the extra pieces of a ball cut into several blobs are left out: balls
    found against balls found plus blobs off every ball."""
    return 100.0 * found / max(found + blobs - on_ball, 1)


def objective(s):
    return min(s[0], s[1]), s[0] + s[1]


def ascend(frames_in_space, lo, hi):
    """First-improvement coordinate ascent: any move that raises the objective is taken."""
    best = score(frames_in_space, lo, hi)
    improved = True
    while improved:
        improved = False
        for bound in range(6):
            for step in STEPS:
                l, h = list(lo), list(hi)
                side = l if bound < 3 else h
                side[bound % 3] = min(255, max(0, side[bound % 3] + step))
                if l[bound % 3] > h[bound % 3] or (l, h) == (lo, hi):
                    continue
                s = score(frames_in_space, l, h)
                if objective(s) > objective(best):
                    best, lo, hi, improved = s, l, h, True
    return best, lo, hi


def calibrated_starts(calibrate_dir, label_class, space):
    run = subprocess.run([CALIBRATE, '--name', 'ball', '--label-class', str(label_class), '--space', space,
                          calibrate_dir], capture_output=True, text=True)
    stats_line = re.search(r'statistics: (.*)', run.stderr)
    class_line = re.search(r'class: \[(.*?)\]\.\.\[(.*?)\]', run.stderr)
    if run.returncode != 0 or not stats_line or not class_line:
        sys.exit('rle_vision_calibrate on %s (%s) failed:\n%s' % (calibrate_dir, space, run.stderr))
    numbers = lambda text: [float(v) for v in re.findall(r'\d+(?:\.\d+)?', text)]  # noqa: E731
    stats = numbers(stats_line.group(1))
    klass = numbers(class_line.group(0))
    mean, sigma = np.array(stats[0:3]), np.array(stats[3:6])
    starts = [(stats[6:9], stats[9:12]), (klass[0:3], klass[3:6])]
    starts += [(mean - k * sigma, mean + k * sigma) for k in (1, 2, 4)]
    return [([int(np.clip(v, 0, 255)) for v in lo], [int(np.clip(v, 0, 255)) for v in hi]) for lo, hi in starts]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--calibrate', required=True, help='the folder make eval calibrates from (for the starts)')
    parser.add_argument('--label-class', type=int, default=0)
    parser.add_argument('--json', help='write the bounds here')
    parser.add_argument('folders', nargs='+', help='the scored folders (their labels are fitted)')
    args = parser.parse_args()
    if not os.access(CALIBRATE, os.X_OK):
        sys.exit('%s is missing: run `make build` first' % CALIBRATE)
    cv2.setNumThreads(1)
    frames = load(args.folders, args.label_class)
    name = lambda folder: os.path.basename(folder.rstrip('/'))  # noqa: E731
    result = {'command': 'scripts/ball_box_bound.py --calibrate %s %s' % (
                  name(args.calibrate), ' '.join(name(f) for f in args.folders)),
              'date': datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d'),
              'scored': [name(f) for f in args.folders], 'spaces': {}}
    for space, code in CONVERSIONS.items():
        in_space = [(cv2.cvtColor(bgr, code), boxes) for bgr, boxes in frames]
        best = None
        for lo, hi in calibrated_starts(args.calibrate, args.label_class, space):
            s, l, h = ascend(in_space, lo, hi)
            if best is None or objective(s) > objective(best[0]):
                best = (s, l, h)
        (recall, precision, blobs, found, on_ball), lo, hi = best
        result['spaces'][space] = {'min': lo, 'max': hi, 'recall_pct': round(recall, 2),
                                   'precision_pct': round(precision, 2), 'blobs': blobs, 'balls_found': found,
                                   'blobs_off_balls': blobs - on_ball,
                                   'precision_pieces_not_counted_pct': round(pieces_not_counted(found, blobs, on_ball), 2)}
        print('%s: best box %s..%s: recall %.1f%%, precision %.1f%% (%d blobs, %d off the balls)' % (
            space, lo, hi, recall, precision, blobs, blobs - on_ball), flush=True)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(result, f, indent=2)
            f.write('\n')
        print('wrote %s' % args.json)


if __name__ == '__main__':
    main()
