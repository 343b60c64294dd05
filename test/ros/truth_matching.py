"""Helpers shared by the rostests: pairing outputs with simulator ground truth, and waiting
for a paused bag's replay pipeline to connect."""
import math
import xmlrpc.client

import rosgraph
import rospy

from waiting import wait_for


def store_by_stamp(lock, table):
    """A subscriber callback keeping each message in `table` under its header stamp, so that
    outputs pair with the ground truth of the same frame."""
    def callback(msg):
        with lock:
            table[msg.header.stamp] = msg
    return callback


def player_connections(player='/play'):
    """Per topic, how many subscribers the player node is connected to (its bus info: the
    master lists a subscriber before that subscriber's connection to the player is made)."""
    try:
        api = rosgraph.Master(rospy.get_name()).lookupNode(player)
        _, _, bus_info = xmlrpc.client.ServerProxy(api).getBusInfo(rospy.get_name())
    except Exception:  # noqa: BLE001 (the player is not up yet)
        return {}
    counts = {}
    for connection in bus_info:
        # [id, destination, direction, transport, topic, connected, ...]; 'o': we publish
        if connection[2] == 'o' and (len(connection) < 6 or connection[5]):
            counts[connection[4]] = counts.get(connection[4], 0) + 1
    return counts


def wait_until_wired(inputs, timeout_s):
    """True once every topic in `inputs` has a subscriber other than this test, the paused
    player (/play) is connected to every subscriber of the inputs it publishes, and its
    /play/pause_playback service is up: a frame played before then would be lost."""
    def wired():
        publishers, subscribers, services = rosgraph.Master(rospy.get_name()).getSystemState()
        nodes = {topic: set(names) - {rospy.get_name()} for topic, names in subscribers}
        played = [t for t, names in publishers if t in inputs and '/play' in names]
        connected = player_connections()
        return (all(nodes.get(t) for t in inputs) and any(s == '/play/pause_playback' for s, _ in services) and
                all(connected.get(t, 0) >= len(nodes.get(t, ())) for t in played))
    return bool(wait_for(wired, timeout_s, period_s=0.2))


def nearest_blob(blobs, obj, max_distance):
    best, best_d = None, max_distance
    for b in blobs.blobs:
        if b.color != obj.color:
            continue
        d = math.hypot(b.cx - obj.cx, b.cy - obj.cy)
        if d <= best_d:
            best, best_d = b, d
    return best, best_d


def iou(a, b):
    """Intersection over union of two inclusive pixel boxes (left, top, right, bottom)."""
    left, top = max(a[0], b[0]), max(a[1], b[1])
    right, bottom = min(a[2], b[2]), min(a[3], b[3])
    inter = max(0, right - left + 1) * max(0, bottom - top + 1)
    area = lambda r: (r[2] - r[0] + 1) * (r[3] - r[1] + 1)  # noqa: E731
    return inter / float(area(a) + area(b) - inter)


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


def segment_length(line):
    return math.hypot(line.x2 - line.x1, line.y2 - line.y1)


def line_angle_difference(a, b):
    d = abs(a - b) % math.pi
    return min(d, math.pi - d)


def near_segment(detected, truth, angle_tol_deg, distance_tol_px):
    """The same edge judged at the truth segment: angles within the tolerance, the detected
    line within distance_tol_px of the truth's midpoint, the segments overlapping along it
    (as src/tools/eval/line_matching.h nearSegment)."""
    if line_angle_difference(detected.theta, truth.theta) > math.radians(angle_tol_deg):
        return False
    mx, my = 0.5 * (truth.x1 + truth.x2), 0.5 * (truth.y1 + truth.y2)
    # Distance of the truth midpoint from the detected line (normal (-sin, cos)).
    nx, ny = -math.sin(detected.theta), math.cos(detected.theta)
    if abs((mx - detected.x1) * nx + (my - detected.y1) * ny) > distance_tol_px:
        return False
    length = segment_length(truth)
    ux, uy = (truth.x2 - truth.x1) / length, (truth.y2 - truth.y1) / length
    a0 = (detected.x1 - truth.x1) * ux + (detected.y1 - truth.y1) * uy
    a1 = (detected.x2 - truth.x1) * ux + (detected.y2 - truth.y1) * uy
    a0, a1 = min(a0, a1), max(a0, a1)
    return a1 > 0 and a0 < length
