#!/usr/bin/env python3
"""Latency under load (make bench-latency): watches a running demo pipeline for a while and
reports the tracker's latency (image stamp to blobs publish, measured inside the tracker and
read from its diagnostics: percentiles since start, and the window's share of frames over each
bound, from two readings of the tracker's counts, so that start-up does not count), tracker
frames dropped (simulator frames that never got blobs),
landmark frames skipped by its one-slot mailbox, and CPU per node.

Usage: latency_probe.py LABEL SECONDS OUT_JSON   (appends one run to OUT_JSON's "runs")."""
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
        self.blob_stamps = set()
        self.status = {}        # node -> {key: value}, latest diagnostics
        rospy.Subscriber('/camera/ground_truth/scene', SceneTruth, self.on_truth, queue_size=1000)
        rospy.Subscriber('/camera/blobs', BlobArray, self.on_blobs, queue_size=1000)
        rospy.Subscriber('/diagnostics', DiagnosticArray, self.on_diagnostics, queue_size=100)

    def on_truth(self, msg):
        with self.lock:
            self.frames.append(msg.header.stamp)

    def on_blobs(self, msg):
        with self.lock:
            self.blob_stamps.add(msg.header.stamp)

    def on_diagnostics(self, msg):
        with self.lock:
            for status in msg.status:
                for node in NODES:
                    if status.name.endswith(': ' + node):
                        self.status[node] = {kv.key: kv.value for kv in status.values}

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
    rospy.init_node('latency_probe')
    probe = Probe()
    deadline = time.time() + 60
    while time.time() < deadline and not (probe.frames and 'tracker' in probe.status and 'landmark' in probe.status):
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
        dropped = sum(1 for stamp in window if stamp not in probe.blob_stamps)
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
        'landmark_skips': int(probe.value('landmark', 'frames dropped (total)') - skips_start),
        'cpu_percent_of_one_core': {node: round(probe.value(node, 'cpu load since start (% of one core)'), 1)
                                    for node in NODES},
        'cpu_percent_manager_process': round(100 * cpu_manager, 1),
        'landmark_ms_mean': probe.value('landmark', 'processing time mean (ms)'),
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
          '%.2f%% over 2 ms  tracker drops %d  landmark skips %d'
          % (label, run['frames'], run['p50_ms'], run['p99_ms'], run['max_ms'], p99_at_most, share_over['2'],
             run['tracker_drops'], run['landmark_skips']))
    print('          CPU (% of one core): ' + ', '.join('%s %.1f' % kv for kv in run['cpu_percent_of_one_core'].items()) +
          '; manager process %.1f' % run['cpu_percent_manager_process'])


if __name__ == '__main__':
    main()
