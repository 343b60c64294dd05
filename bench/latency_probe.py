#!/usr/bin/env python3
"""Latency under load (make bench-latency): watches a running demo pipeline for a while and
reports the tracker's latency (image stamp to blobs publish, measured inside the tracker and
read from its diagnostics: percentiles since start, and the window's share of frames over each
bound, from two readings of the tracker's counts, so that start-up does not count), tracker
frames dropped (simulator frames that never got blobs),
landmark frames skipped by its one-slot mailbox, CPU per node, and the tracker's slowest frame
in the window (wall-clock, from the blobs messages, and thread CPU time, from diagnostics).

Usage: latency_probe.py LABEL SECONDS OUT_JSON [--no-landmark]   (appends one run to OUT_JSON's
"runs"; --no-landmark: the pipeline runs the tracker alone)."""
import json
import os
import sys
import threading
import time

import rosgraph
import rospy
import xmlrpc.client
from diagnostic_msgs.msg import DiagnosticArray
from rle_vision.msg import BlobArray, SceneTruth

NODES = ('simulator', 'tracker', 'edge detector', 'landmark', 'ground projector')
BOUNDS_MS = ('0.5', '1', '1.5', '2', '3', '5')  # the tracker counts frames over each


def latency_counts(probe):
    counts = {b: probe.value('tracker', 'latency frames over %s ms (since start)' % b) for b in BOUNDS_MS}
    counts['all'] = probe.value('tracker', 'latency frames (since start)')
    return counts


def window_latency(start, end):
    """Frames in the window, the share over each bound (%), and the smallest bound the p99 is at
    or below (None when over every bound)."""
    frames = end['all'] - start['all']
    share = {b: 100.0 * (end[b] - start[b]) / frames if frames else float('nan') for b in BOUNDS_MS}
    p99_at_most = next((float(b) for b in BOUNDS_MS if share[b] <= 1.0), None)
    return int(frames), share, p99_at_most


class Probe:
    def __init__(self):
        self.lock = threading.Lock()
        self.frames = []        # stamps of simulator frames
        self.frame_ms = {}      # blobs stamp -> the tracker's processing_time_ms
        self.cpu_max_ms = []    # (time, the tracker's 'processing cpu time max (ms)' of a report)
        self.status = {}        # node -> {key: value}, latest diagnostics
        rospy.Subscriber('/camera/ground_truth/scene', SceneTruth, self.on_truth, queue_size=1000)
        rospy.Subscriber('/camera/blobs', BlobArray, self.on_blobs, queue_size=1000)
        rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diagnostics, queue_size=100)

    def on_truth(self, msg):
        with self.lock:
            self.frames.append(msg.header.stamp)

    def on_blobs(self, msg):
        with self.lock:
            self.frame_ms[msg.header.stamp] = msg.processing_time_ms

    def on_diagnostics(self, msg):
        with self.lock:
            for status in msg.status:
                for node in NODES:
                    if status.name.endswith(': ' + node):
                        self.status[node] = {kv.key: kv.value for kv in status.values}
                        if node == 'tracker' and 'processing cpu time max (ms)' in self.status[node]:
                            self.cpu_max_ms.append((time.time(), float(self.status[node]['processing cpu time max (ms)'])))

    def value(self, node, key, default=float('nan')):
        with self.lock:
            return float(self.status.get(node, {}).get(key, default))


def process_cpu_seconds(node_name):
    """CPU time (user + system, s) of the process running a ROS node."""
    api = rosgraph.Master('/latency_probe').lookupNode(node_name)
    pid = xmlrpc.client.ServerProxy(api).getPid('/latency_probe')[2]
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def machine_name():
    with open('/proc/cpuinfo') as f:
        for line in f:
            if line.startswith('model name'):
                return line.split(':', 1)[1].strip()
    return 'unknown'


def spread(runs):
    """Per configuration (the label before '#'): the runs' window p99 bounds, share over 2 ms and drops."""
    configs = {}
    for r in runs:
        configs.setdefault(r['label'].split('#')[0], []).append(r)
    return {config: {'runs': len(rs),
                     'window_p99_at_most_ms': [r.get('window_p99_at_most_ms') for r in rs],
                     'window_percent_over_2ms': [round(r['window_percent_over_ms']['2'], 2) for r in rs
                                                 if 'window_percent_over_ms' in r],
                     'p99_since_start_ms': [r['p99_ms'] for r in rs],
                     'tracker_drops': [r['tracker_drops'] for r in rs]}
            for config, rs in configs.items()}


def main():
    label, seconds, out_path = sys.argv[1], float(sys.argv[2]), sys.argv[3]
    with_landmark = '--no-landmark' not in sys.argv[4:]
    rospy.init_node('latency_probe')
    probe = Probe()
    deadline = time.time() + 60
    while time.time() < deadline and not (probe.frames and 'tracker' in probe.status and
                                          ('landmark' in probe.status or not with_landmark)):
        time.sleep(0.2)
    time.sleep(3.0)  # the pipeline settles
    skips_start = probe.value('landmark', 'frames dropped (total)')
    latency_start = latency_counts(probe)
    cpu_start = process_cpu_seconds('/camera/vision_manager')
    wall_start = time.time()
    with probe.lock:
        first = len(probe.frames)
    time.sleep(seconds)
    with probe.lock:
        window = probe.frames[first:]
    time.sleep(1.5)  # the last frames' blobs and a fresh diagnostics report arrive
    cpu_manager = (process_cpu_seconds('/camera/vision_manager') - cpu_start) / (time.time() - 1.5 - wall_start)
    with probe.lock:
        dropped = sum(1 for stamp in window if stamp not in probe.frame_ms)
        frame_ms = [probe.frame_ms[stamp] for stamp in window if stamp in probe.frame_ms]
        # Reports whose 1-s span lies inside the window.
        cpu_max = [ms for t, ms in probe.cpu_max_ms if wall_start + 1.0 <= t <= wall_start + seconds]
    window_frames, share_over, p99_at_most = window_latency(latency_start, latency_counts(probe))
    run = {
        'label': label,
        'seconds': seconds,
        'frames': len(window),
        'p50_ms': probe.value('tracker', 'latency image stamp to blobs p50 (ms)'),
        'p99_ms': probe.value('tracker', 'latency image stamp to blobs p99 (ms)'),
        'max_ms': probe.value('tracker', 'latency image stamp to blobs max (ms)'),
        'latency_frames': probe.value('tracker', 'latency frames (since start)'),
        'window_latency_frames': window_frames,
        'window_percent_over_ms': share_over,
        'window_p99_at_most_ms': p99_at_most,
        'tracker_drops': dropped,
        'landmark_skips': int(probe.value('landmark', 'frames dropped (total)') - skips_start) if with_landmark else None,
        'tracker_frame_ms_max': max(frame_ms, default=float('nan')),
        'tracker_frames_over_5ms': sum(1 for ms in frame_ms if ms > 5.0),
        'tracker_cpu_ms_max': max(cpu_max, default=float('nan')),
        'cpu_percent_of_one_core': {node: round(probe.value(node, 'cpu load since start (% of one core)'), 1)
                                    for node in NODES if node in probe.status},
        'cpu_percent_manager_process': round(100 * cpu_manager, 1),
        'landmark_ms_mean': probe.value('landmark', 'processing time mean (ms)') if with_landmark else None,
        'tracker_ms_mean': probe.value('tracker', 'processing time mean (ms)'),
    }
    results = {'runs': []}
    if os.path.exists(out_path):
        with open(out_path) as f:
            results = json.load(f)
    results['runs'] = [r for r in results.get('runs', []) if r.get('label') != label] + [run]
    results['spread'] = spread(results['runs'])
    results['machine'] = machine_name()
    results['date'] = time.strftime('%Y-%m-%d', time.gmtime())
    with open(out_path, 'w') as f:
        json.dump(results, f, indent=2)
    print('%-18s %6d frames  latency p50 %.2f ms  p99 %.2f ms  max %.2f ms (since start); window: p99 <= %s ms, '
          '%.2f%% over 2 ms  tracker drops %d  landmark skips %s; slowest frame %.2f ms (CPU %.2f ms), %d over 5 ms'
          % (label, run['frames'], run['p50_ms'], run['p99_ms'], run['max_ms'], p99_at_most, share_over['2'],
             run['tracker_drops'], run['landmark_skips'], run['tracker_frame_ms_max'], run['tracker_cpu_ms_max'],
             run['tracker_frames_over_5ms']))
    print('          CPU (% of one core): ' + ', '.join('%s %.1f' % kv for kv in run['cpu_percent_of_one_core'].items()) +
          '; manager process %.1f' % run['cpu_percent_manager_process'])


if __name__ == '__main__':
    main()
