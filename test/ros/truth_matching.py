"""Helpers shared by the rostests: pairing outputs with simulator ground truth."""
import math


def nearest_blob(blobs, obj, max_distance):
    best, best_d = None, max_distance
    for b in blobs.blobs:
        if b.color != obj.color:
            continue
        d = math.hypot(b.cx - obj.cx, b.cy - obj.cy)
        if d <= best_d:
            best, best_d = b, d
    return best, best_d


def perimeter(o):
    return 2.0 * ((o.right - o.left + 1) + (o.bottom - o.top + 1))


def clear_objects(truth, min_area):
    """Whole objects surrounded only by ground or sky: with lens blur, a boundary shared with
    another box mixes two object colours that neither class accepts, which biases the blob."""
    return [o for o in whole_objects(truth, min_area) if not o.touches_other_box]


def whole_objects(truth, min_area):
    """Ground-truth objects whose visible mask is exactly one blob for a colour tracker: one
    piece, touching no box of the same colour."""
    return [o for o in truth.objects
            if o.area >= min_area and o.pieces == 1 and not o.touches_same_color]
