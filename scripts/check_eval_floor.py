#!/usr/bin/env python3
"""Checks our figures in make-eval results against the floor kept in the repository
(bench/eval_floor.json): the best figures landed so far. Falling below the floor fails (exit 1);
reaching the targets (docs/ARCHITECTURE.md, the issues' targets) is reported. The floor only
rises: when a change improves a figure, raise it in bench/eval_floor.json in the same commit.

  check_eval_floor.py [--horizon EVAL_HORIZON.json] [--balls EVAL_BALLS.json] [--field EVAL_FIELD.json]
                      [--balls-by-date EVAL_BALLS_BY_DATE.json] [--verifier EVAL_VERIFIER.json]
                      --floor FLOOR.json"""
import argparse
import json
import sys

# (key, better: 'higher' or 'lower', target or None)
# The horizon: over every labelled UAV frame, each flight scored by a model fitted without it.
HORIZON_CHECKS = [
    ('pass_pct', 'higher', 97.0),
    ('worst_group_pass_pct', 'higher', 90.0),
    ('angle_error_mean_deg', 'lower', 1.0),
    ('on_horizon_pct', 'higher', None),  # target: at least FastLineDetector's in the same run
]
HORIZON_OURS = 'ours, model held out (leave one group out)'
FLD = 'FastLineDetector (longest level)'
# Frames without a horizon: the share on which none is reported (the same held-out models).
NO_HORIZON_CHECKS = [('pass_pct', 'higher', 98.0)]
NO_HORIZON_SETS = {'robocup_msl': 'no_horizon_msl', 'simulator scene_indoor': 'no_horizon_sim_indoor'}
# Balls on the folders not calibrated on: the targets are for learning over the sequence
# (issue 15); learning and the fixed calibrated range are each gated by their floor meanwhile.
BALL_CHECKS = [
    ('recall_pct', 'higher', 90.0),
    ('precision_pct', 'higher', 90.0),
]
BALLS_OURS = 'ours, calibrated range (fixed)'
BALLS_LEARNING = 'ours, --sequence, learning from blobs'
# The field boundary on the robot frames (each frame alone): labelled robots on the field side,
# over all dates and on the worst date (issue 29's target: 99%; robots parked beyond the field
# are labelled too, so the figures are floors on the boundary's accuracy).
FIELD_CHECKS = [
    ('all.obstacle_on_field_pct', 'higher', 99.0),
    ('worst_date_obstacle_on_field_pct', 'higher', 99.0),
]
# The ball class calibrated on one date and scored on another, every pair of dates (grouped
# cross-validation), keeping only blobs on the field side (issue 29's target: 80% precision on
# every pair, at a recall of the balls on the field side no lower than without the filter).
BALLS_BY_DATE_CHECKS = [
    ('worst.ours_on_field.precision_pct', 'higher', 80.0),
    ('all.ours_on_field.precision_pct', 'higher', None),
    ('all.ours_on_field.recall_on_field_pct', 'higher', None),  # target: the same without the filter
]
# The ball verifier (issue 30): each date held out, calibrated and trained on the others.
VERIFIER_CHECKS = [
    ('pooled.verified.recall_pct', 'higher', 93.0),
    ('pooled.verified.precision_pct', 'higher', 93.0),
    ('worst.verified.recall_pct', 'higher', 90.0),
    ('worst.verified.precision_pct', 'higher', 90.0),
]
SLACK = 1e-6


def check(label, ours, floor, checks, targets_from=None):
    failures = []
    for key, better, target in checks:
        value, low = ours[key], floor.get(key)
        if target is None and targets_from is not None:
            target = targets_from[key]
        met = target is None or (value >= target if better == 'higher' else value <= target)
        regressed = low is not None and (value < low - SLACK if better == 'higher' else value > low + SLACK)
        print('[eval floor] %-7s %-24s ours %8.2f   floor %8s   target %8s  %s%s' % (
            label, key, value, '-' if low is None else '%.2f' % low, '-' if target is None else '%.2f' % target,
            'met' if met else 'not met', '   REGRESSION' if regressed else ''))
        if regressed:
            failures.append(label + ' ' + key)
    return failures


def check_horizon(result, floor):
    methods = result['methods']
    ours, fld = methods[HORIZON_OURS], methods[FLD]
    failures = check('horizon', ours, floor['horizon'], HORIZON_CHECKS, targets_from=fld)
    print('[eval floor] horizon worst flight: %s' % ours['worst_group'])
    for dataset, key in NO_HORIZON_SETS.items():
        if dataset in result['datasets']:
            failures += check(key, result['datasets'][dataset][HORIZON_OURS], floor[key], NO_HORIZON_CHECKS)
    rows = result['robustness']
    lowest = min(rows, key=lambda name: rows[name]['pass_pct'])
    below_fld = [name for name, row in rows.items() if row['pass_pct'] < row['fld_pass_pct']]
    failures += check('robust', {'min_pass_pct': rows[lowest]['pass_pct']}, floor['robustness'],
                      [('min_pass_pct', 'higher', 95.0)])
    print('[eval floor] robustness: lowest %s; below FastLineDetector: %s' % (lowest, ', '.join(below_fld) or 'none'))
    print('[eval floor] horizon time: ours %.2f ms, FastLineDetector %.2f ms per frame (%.2fx; not gated: see make bench)'
          % (ours['ms_per_frame'], fld['ms_per_frame'], ours['ms_per_frame'] / fld['ms_per_frame']))
    return failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--horizon')
    parser.add_argument('--balls')
    parser.add_argument('--field')
    parser.add_argument('--balls-by-date')
    parser.add_argument('--verifier')
    parser.add_argument('--floor', required=True)
    args = parser.parse_args()
    floor = json.load(open(args.floor))
    failures = []
    if args.horizon:
        failures += check_horizon(json.load(open(args.horizon)), floor)
    if args.balls:
        methods = json.load(open(args.balls))['methods']
        failures += check('balls', methods[BALLS_OURS], floor['balls'], BALL_CHECKS)
        failures += check('learning', methods[BALLS_LEARNING], floor['balls_learning'], BALL_CHECKS)
    if args.field:
        failures += check('field', json.load(open(args.field)), floor['field'], FIELD_CHECKS)
    if args.balls_by_date:
        result = json.load(open(args.balls_by_date))
        targets = {'all.ours_on_field.precision_pct': None,
                   'all.ours_on_field.recall_on_field_pct': result['all.ours.recall_on_field_pct']}
        failures += check('by date', result, floor['balls_by_date'], BALLS_BY_DATE_CHECKS, targets_from=targets)
    if args.verifier:
        failures += check('verifier', json.load(open(args.verifier)), floor['verifier'], VERIFIER_CHECKS)
    if failures:
        print('[eval floor] below the floor of %s: %s' % (args.floor, ', '.join(failures)))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
