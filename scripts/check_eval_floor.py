#!/usr/bin/env python3
"""Checks our figures in a make-eval result against the floor kept in the repository
(bench/eval_floor.json): the best figures landed so far. Falling below the floor fails (exit 1);
reaching the targets (docs/DESIGN.md section 5) is reported. The floor only rises: when a change
improves a figure, raise it in bench/eval_floor.json in the same commit.

  check_eval_floor.py RESULT.json FLOOR.json"""
import json
import sys

# (key, better: 'higher' or 'lower', target or None)
CHECKS = [
    ('pass_pct', 'higher', 97.0),
    ('angle_error_mean_deg', 'lower', 1.0),
    ('distance_error_mean_px', 'lower', 8.0),
    ('on_horizon_pct', 'higher', None),  # target: at least FastLineDetector's in the same run
    ('confident_pass_pct', 'higher', 95.0),
]
OURS = 'ours (rle_vision, defaults)'
FLD = 'FastLineDetector (longest level)'
SLACK = 1e-6


def main(result_path, floor_path):
    result = json.load(open(result_path))['methods']
    ours, fld = result[OURS], result[FLD]
    floor = json.load(open(floor_path))
    failures = []
    for key, better, target in CHECKS:
        value, low = ours[key], floor.get(key)
        if target is None and key == 'on_horizon_pct':
            target = fld[key]
        met = target is None or (value >= target if better == 'higher' else value <= target)
        regressed = low is not None and (value < low - SLACK if better == 'higher' else value > low + SLACK)
        print('[eval floor] %-24s ours %8.2f   floor %8s   target %8s  %s%s' % (
            key, value, '-' if low is None else '%.2f' % low, '-' if target is None else '%.2f' % target,
            'met' if met else 'not met', '   REGRESSION' if regressed else ''))
        if regressed:
            failures.append(key)
    ratio = ours['ms_per_frame'] / fld['ms_per_frame']
    print('[eval floor] time: ours %.2f ms, FastLineDetector %.2f ms per frame (%.2fx; target <= 1, not gated: '
          'see make bench)' % (ours['ms_per_frame'], fld['ms_per_frame'], ratio))
    if failures:
        print('[eval floor] below the floor of %s: %s' % (floor_path, ', '.join(failures)))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1], sys.argv[2]))
