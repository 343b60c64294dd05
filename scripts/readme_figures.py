#!/usr/bin/env python3
"""The tables of measured figures in docs/performance.md, written from the committed files the
benchmarks and the evaluations record (bench/results/*.json, each with its machine and date),
so that a figure cannot drift from its run. A table sits between `<!-- figures: NAME -->` and
`<!-- /figures -->`; NAME picks the writer below.

  readme_figures.py --write   rewrite the tables in docs/performance.md from bench/results/
  readme_figures.py --check   exit 1, naming the tables that differ (make test runs this)

`make bench RECORD=1` (eval, bench-latency) records a run into bench/results/ and runs --write;
commit both."""
import argparse
import json
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = os.path.join(ROOT, 'bench', 'results')
REGION = re.compile(r'(<!-- figures: (\w+) -->\n)(.*?)(<!-- /figures -->)', re.S)


def load(name):
    with open(os.path.join(RESULTS, name + '.json')) as f:
        return json.load(f)


def ms(value, digits=2):
    return '%.*f ms' % (digits, value)


def provenance(command, name, data):
    return '(`%s` on %s, %s: `bench/results/%s.json`)' % (command, data.get('date', '?'), data.get('machine', '?'), name)


def table(header, rows):
    lines = ['| ' + ' | '.join(header) + ' |', '|' + '---|' * len(header)]
    lines += ['| ' + ' | '.join(str(c) for c in row) + ' |' for row in rows]
    return '\n'.join(lines)


def tracker():
    d = load('tracker')
    rows = [
        ['tracker core, bgr8 (classify + RLE + regions + tracking)', ms(d['tracker_ms'], 3), '≤ 0.5 ms'],
        ['tracker core, yuv422 (UYVY)', ms(d['tracker_yuv422_ms'], 3), 'faster than CMVision on the same frame (measured outside the project: below)'],
        ['tracker core, bgr8, a new colour table swapped in every frame (built on the other CPU)',
         '%s (%.2f swaps per frame)' % (ms(d['tracker_ms_with_updates'], 3), d['table_swaps_per_frame']), '≤ 0.5 ms'],
        ['OpenCV `cvtColor` + `inRange` + `connectedComponentsWithStats` per class', ms(d['opencv_ms'], 1), ''],
        ['speedup vs OpenCV', '%.0fx' % d['speedup_vs_opencv'], '≥ 10x'],
        ['`memcpy` of the frame', ms(d['memcpy_ms'], 3), ''],
        ['tracker / memcpy', '%.0fx' % d['ratio_to_memcpy'], '≤ 25x'],
    ]
    if 'verifier_ms' in d:
        rows += [
            ['the same frame with 50 ball-coloured discs drawn (%d candidates): tracker alone' % d['verifier_candidates'],
             ms(d['verifier_frame_tracker_ms'], 3), ''],
            ['ball verifier (`config/ball_verifier.yml.gz`) on its %d largest candidates: features and score'
             % d['verifier_scored'], ms(d['verifier_ms'], 3), '≤ 0.2 ms at 50 candidates'],
        ]
    return table(['', 'measured', 'target'], rows) + '\n\n' + provenance('make bench', 'tracker', d)


def tracker_noise():
    d = load('tracker')
    rows = [['noise σ = 25', '**%s**' % ms(d['tracker_noise25_ms'], 3), ms(d['tracker_noise25_yuv422_ms'], 3),
             ms(d['opencv_noise25_ms']), 'bgr8 ≤ 0.30 ms'],
            ['noise σ = 60', ms(d['tracker_noise60_ms']), ms(d['tracker_noise60_yuv422_ms']), ms(d['opencv_noise60_ms']), '']]
    if d.get('tracker_real_ms', 0) > 0:
        rows.append(['608x800 real frame', ms(d['tracker_real_ms'], 3), ms(d['tracker_real_yuv422_ms'], 3),
                     ms(d['opencv_real_ms']), ''])
    return (table(['frame', 'bgr8', 'yuv422 (UYVY)', 'OpenCV pipeline', 'target'], rows) + '\n\n' +
            provenance('make bench', 'tracker', d))


def tracker_bounded():
    d = load('tracker')
    met = lambda value, bound: '≤ %s ms: %s' % (bound, 'met' if value <= bound else '**not met**')  # noqa: E731
    rows = []
    for sigma, bgr_bound, uyvy_bound in (('25', 0.5, None), ('60', 3.0, 1.6)):
        k = 'bounded_noise%s_' % sigma
        rows += [
            ['σ = %s (%d regions bgr8, %d yuv422)' % (sigma, d[k + 'regions'], d[k + 'regions_yuv422']),
             'segment only (every region built)', ms(d[k + 'segment_ms'], 3), ms(d[k + 'segment_yuv422_ms'], 3), ''],
            ['', '**segment + tracker** (the Tracker nodelet)', ms(d[k + 'tracker_ms'], 3),
             ms(d[k + 'tracker_yuv422_ms'], 3),
             ', '.join(x for x in ('bgr8 ' + met(d[k + 'tracker_ms'], bgr_bound),
                                   uyvy_bound and 'yuv422 ' + met(d[k + 'tracker_yuv422_ms'], uyvy_bound)) if x)],
            ['', 'segment + tracking every region (`min_track_area_px` 1, no limit)', ms(d[k + 'every_region_ms'], 1),
             ms(d[k + 'every_region_yuv422_ms'], 1), ''],
        ]
    return (table(['frame', '', 'bgr8', 'yuv422 (UYVY)', 'target'], rows) + '\n\n' +
            provenance('make bench', 'tracker', d))


def tracker_noise_ratios():
    d = load('tracker')
    if 'noise25_to_clean_tracker_ratio' not in d:
        raise KeyError('noise25_to_clean_tracker_ratio (make bench writes it)')
    met = lambda value, bound: '%.3fx (≤ %gx: %s)' % (value, bound, 'met' if value <= bound else '**not met**')  # noqa: E731
    # The defaults per path, then the options that change labels (bench_tracker.cpp noiseOptions).
    columns = ['', '_yuv422', '_pair_chroma', '_flip_filter_yuv422', '_pair_chroma_flip_filter']
    rows = []
    for sigma, bound in (('25', 1.3), ('60', 3)):
        rows.append(['noise σ = %s / clean' % sigma] +
                    [met(d['noise%s_to_clean_tracker%s_ratio' % (sigma, c)], bound) for c in columns])
    if d.get('real_ratio_frames', 0) > 0:
        rows.append(['%d real robot frames / clean, per pixel' % d['real_ratio_frames']] +
                    ['%.2fx' % d['real_to_clean_tracker%s_ratio_per_pixel' % c] for c in columns])
    rows.append(['clean frame (the ratios\' base, timed in turns with them)'] +
                [ms(d['noise_ratio_clean_tracker%s_ms' % c], 3) for c in columns])
    rows.append(['runs, σ = 25 / σ = 60'] + ['%d / %d' % (d['bounded_noise25_runs%s' % r], d['bounded_noise60_runs%s' % r])
                                              for r in columns])
    return (table(['segment + tracker, `colors.txt`', 'bgr8', 'yuv422 (UYVY)', 'bgr8, `bgr_pair_chroma`',
                   'yuv422, `flip_filter_px` 2', 'bgr8, `bgr_pair_chroma` + `flip_filter_px` 2'], rows) +
            '\n\n' + provenance('make bench', 'tracker', d))


def landmark():
    d = load('landmark')
    x = lambda ours, theirs: theirs / ours  # noqa: E731
    met = lambda ok: 'met' if ok else '**not met**'  # noqa: E731
    rows = [
        ['our 5x5 Sobel, 3 channels, max magnitude', ms(d['sobel_ms']), 'faster than `cv::Sobel`'],
        ['`cv::Sobel` ksize 5, x and y derivatives only', '%s (ours %.1fx faster)' % (
            ms(d['opencv_sobel_derivatives_only_ms']), x(d['sobel_ms'], d['opencv_sobel_derivatives_only_ms'])), ''],
        ['`cv::Sobel` + float magnitude + max over channels (the same job, buffers reused)', '%s (ours %.1fx faster)' % (
            ms(d['opencv_sobel_ms']), x(d['sobel_ms'], d['opencv_sobel_ms'])), ''],
        ['landmark total: Sobel + RLE Hough + horizon (region search and edge refinement)', ms(d['landmark_total_ms']),
         '≤ 3 ms: ' + met(d['landmark_total_ms'] <= 3.0)],
        ['`cvtColor` + `cv::ximgproc::FastLineDetector` (defaults) on the same frame', ms(d['fld_ms']), ''],
        ['`cvtColor` + `cv::createLineSegmentDetector` (LSD, refine standard)', ms(d['lsd_ms'], 1), ''],
        ['RLE Hough + horizon on the edge image (lines-only horizon)', ms(d['hough_ms']), ''],
        ['… of which the RLE into edge objects (thinning, runs, union-find)', ms(d['edge_objects_ms']), ''],
        ['… of which the Hough on the edge objects (sampling, votes, peaks, refits)', ms(d['hough_only_ms']), ''],
        ['`cv::HoughLinesP` on the same edge image', '%s (ours %.1fx; the Hough alone %.1fx)' % (
            ms(d['opencv_houghp_ms']), d['speedup_vs_houghp'], d['speedup_vs_houghp_hough_only']), ''],
        ['line recall / precision, ours (2°, 2 px at the true segment)', '%.2f / %.2f' % (d['recall'], d['precision']),
         'recall ≥ 0.89 at precision ≥ 0.95: ' + met(d['recall'] >= 0.89 and d['precision'] >= 0.95)],
        ['line recall / precision, `cv::HoughLinesP`', '%.2f / %.2f' % (d['opencv_recall'], d['opencv_precision']), ''],
        ['line recall / precision, FastLineDetector (its segments ≥ 30 px)', '%.2f / %.2f' % (d['fld_recall'], d['fld_precision']), ''],
        ['line recall / precision, LSD (its segments ≥ 30 px)', '%.2f / %.2f' % (d['lsd_recall'], d['lsd_precision']), ''],
    ]
    for key, what in (('real_', '`uav_horizon`, every 10th, 480x480'), ('msl_', '`robocup_msl`, every 15th, 608x800')):
        if d.get(key + 'frames', 0) <= 0:
            continue
        rows += [
            ['real frames (%d of %s): ours, Sobel + RLE Hough + horizon (the shipped horizon model)' % (d[key + 'frames'], what),
             ms(d[key + 'frame_ms']), '≤ 0.5x FastLineDetector: ' + met(d[key + 'frame_ms'] <= 0.5 * d[key + 'frame_fld_ms'])],
            ['… `cvtColor` + FastLineDetector / LSD / Gauss + Canny + HoughLinesP', '%.2f / %.1f / %.2f ms (ours %.2fx / %.2fx / %.2fx their time)' % (
                d[key + 'frame_fld_ms'], d[key + 'frame_lsd_ms'], d[key + 'frame_houghp_ms'], d[key + 'frame_ms'] / d[key + 'frame_fld_ms'],
                d[key + 'frame_ms'] / d[key + 'frame_lsd_ms'], d[key + 'frame_ms'] / d[key + 'frame_houghp_ms']), '']]
        if key + 'sobel_ms' in d:
            rows.append(['… ours per stage: Sobel / edge objects / Hough / horizon', '%.2f / %.2f / %.2f / %.2f ms' % (
                d[key + 'sobel_ms'], d[key + 'objects_ms'], d[key + 'hough_ms'], d[key + 'horizon_ms']), ''])
        if key + 'field_ms' in d:
            rows.append(['… the field stage (floor colour followed, boundary; not part of the total)',
                         ms(d[key + 'field_ms']), '≤ 0.3 ms (640x480) in the tracker\'s thread; it runs in the landmark\'s'])
        if key + 'frames_budget_cut' in d:
            rows.append(['… frames whose line budget (`max_refinements_per_frame`) ran out', '%d of %d' % (
                d[key + 'frames_budget_cut'], d[key + 'frames']), ''])
    rows += [['sample pairs per frame: RLE per object / global random Hough (eq. 4)', '%.1fk / %.0fk' % (
                 d['sample_pairs_rle'] / 1e3, d['sample_pairs_global'] / 1e3), ''],
             ['horizon angle error, median', '%.3f°' % d['horizon_err_deg_median'], '< 0.5°']]
    return table(['', 'measured', 'target'], rows) + '\n\n' + provenance('make bench', 'landmark', d)


def eval_horizon():
    d = load('eval_horizon')
    names = {'ours, model held out (leave one group out)': 'ours, each flight held out from the model',
             'ours, shipped model (in sample)': 'ours, the shipped model (in sample)',
             'ours, evidence product (no model)': 'ours, evidence product (before the model)',
             'FastLineDetector (longest level)': 'FastLineDetector', 'LSD (longest level)': 'LSD',
             'HoughLinesP (longest level)': 'Gauss + Canny + HoughLinesP'}
    sets = [k for k in d['datasets'] if k.startswith('uav')]
    rows = []
    for key, m in d['methods'].items():
        name = names.get(key, key)
        passed = '%.1f%%' % m['pass_pct']
        rows.append([name, '**%s**' % passed if 'held out' in name else passed] +
                    ['%.1f%%' % d['datasets'][s][key]['pass_pct'] for s in sets] +
                    ['%s %.1f%%' % (m['worst_group'], m['worst_group_pass_pct']), '%.1f%%' % m['found_pct'],
                     '%.2f° / %.2f°' % (m['angle_error_mean_deg'], m['angle_error_median_deg']),
                     '%.1f px' % m['distance_error_mean_px'], '%.1f%%' % m['on_horizon_pct'], '%.2f' % m['ms_per_frame']])
    return (table(['method', 'pass, all %d' % d['frames']] + ['pass, `%s`' % s for s in sets] +
                  ['worst flight', 'found', 'angle error mean / median', 'distance error mean', 'on horizon',
                   'ms/frame'], rows) + '\n\n' + provenance('make eval', 'eval_horizon', d))


def eval_no_horizon():
    d = load('eval_horizon')
    sets = [k for k in d['datasets'] if not k.startswith('uav') and 'scene_default' not in k]  # no horizon in view
    rows = []
    for key in d['methods']:
        rows.append([key] + ['%.1f%%' % d['datasets'][s][key]['pass_pct'] for s in sets])
    return (table(['method'] + ['no horizon reported, `%s` (%d frames)' % (s, d['datasets'][s][key]['frames'])
                                for s in sets], rows) + '\n\n' + provenance('make eval', 'eval_horizon', d))


def eval_robustness():
    d = load('eval_horizon')
    rows = [[name, '**%.1f%%**' % r['pass_pct'], '%.1f%%' % r['fld_pass_pct']] for name, r in d['robustness'].items()]
    return (table(['perturbation (all labelled frames)', 'ours, each flight held out', 'FastLineDetector'], rows) +
            '\n\n' + provenance('make eval', 'eval_horizon', d))


def eval_balls():
    d = load('eval_balls')
    methods = list(d['methods'])
    cell = lambda s: 'recall %.1f%%, precision %.1f%% (%d blobs), %.2f ms/frame' % (  # noqa: E731
        s['recall_pct'], s['precision_pct'], s['blobs'], s['ms_per_frame'])
    rows = []
    for folder, by_method in d['folders'].items():
        rows.append([folder, by_method[methods[0]]['balls']] + [cell(by_method[m]) for m in methods])
    rows.append(['all', d['methods'][methods[0]]['balls']] + ['**%s**' % cell(d['methods'][m]) for m in methods])
    return (table(['folder', 'balls'] + methods, rows) + '\n\n' + provenance('make eval', 'eval_balls', d) +
            '; range calibrated on `%s`: min %s, max %s' % (os.path.basename(d['calibrated_on']), d['range']['min'],
                                                          d['range']['max']))


def eval_balls_bound():
    d = load('eval_balls_bound')
    rows = [[space, '%s..%s' % (b['min'], b['max']), '%.1f%%' % b['recall_pct'], '%.1f%%' % b['precision_pct'],
             b['blobs'], b['blobs_off_balls'], '%.1f%%' % b['precision_pieces_not_counted_pct']]
            for space, b in d['spaces'].items()]
    return (table(['space', 'best box found (fitted to the scored labels)', 'recall', 'blob precision', 'blobs',
                   'blobs off the balls', 'precision, extra pieces of a ball not counted'], rows) +
            '\n\n(`%s` on %s: `bench/results/eval_balls_bound.json`; scored on %s)' % (
                d['command'], d['date'], ', '.join(d['scored'])))


def eval_field():
    d = load('eval_field')
    groups = sorted({k.split('.')[1] for k in d if k.startswith('dates.')}) + ['all']
    rows = []
    for g in groups:
        key = 'all' if g == 'all' else 'dates.' + g
        cells = ['%.1f%% of %d' % (d[key + '.%s_on_field_pct' % c], d[key + '.%s_objects' % c])
                 for c in ('ball', 'obstacle', 'human')]
        rows.append([('**%s**' % g) if g == 'all' else g, int(d[key + '.frames']),
                     '%.1f%%' % d[key + '.boundary_found_pct']] + cells + [ms(d[key + '.ms_per_frame'])])
    return (table(['date', 'frames', 'boundary found', 'balls on the field side', 'robots on the field side',
                   'people on the field side', 'field stage (seeded per frame)'], rows) +
            '\n\n' + provenance('make eval', 'eval_field', d))


def eval_balls_by_date():
    d = load('eval_balls_by_date')
    pairs = sorted({k.split('.')[1] for k in d if k.startswith('pairs.')})
    methods = [('ours', 'fixed range'), ('ours_on_field', 'on the field side only')]

    def cells(key):
        out = []
        for m, _ in methods:
            out += ['%.1f%%' % d['%s.%s.recall_pct' % (key, m)], '%.1f%%' % d['%s.%s.recall_on_field_pct' % (key, m)],
                    '%.1f%% of %d' % (d['%s.%s.precision_pct' % (key, m)], d['%s.%s.blobs' % (key, m)])]
        return out
    rows = [[p.replace('_to_', ' → '), int(d['pairs.%s.ours.balls' % p])] + cells('pairs.' + p) for p in pairs]
    rows.append(['**all pairs**', int(d['all.ours.balls'])] + cells('all'))
    worst = ['**worst pair**', ''] + sum([['%.1f%%' % d['worst.%s.recall_pct' % m],
                                            '%.1f%%' % d['worst.%s.recall_on_field_pct' % m],
                                            '%.1f%%' % d['worst.%s.precision_pct' % m]] for m, _ in methods], [])
    rows.append(worst)
    header = ['calibrated on → scored on', 'balls']
    for _, name in methods:
        header += ['recall (%s)' % name, 'recall of balls on the field side', 'blob precision']
    return table(header, rows) + '\n\n' + provenance('make eval', 'eval_balls_by_date', d)


def eval_verifier():
    d = load('eval_verifier')
    dates = sorted({k.split('.')[1] for k in d if k.startswith('dates.')})
    methods = [('range', 'calibrated range alone'), ('candidates', 'candidates (range covering each training date\'s, widened by %d)' % d['widen_levels']),
               ('verified', 'candidates + verifier'), ('verified_on_field', 'candidates + verifier, field side only')]
    rows = []
    for g in dates + ['pooled']:
        key = 'pooled' if g == 'pooled' else 'dates.' + g
        for m, name in methods:
            rows.append([('**%s**' % g) if g == 'pooled' else g, name, int(d['%s.%s.balls' % (key, m)]),
                         '%.1f%%' % d['%s.%s.recall_pct' % (key, m)], '%.1f%%' % d['%s.%s.recall_on_field_pct' % (key, m)],
                         '%.1f%% of %d' % (d['%s.%s.precision_pct' % (key, m)], d['%s.%s.blobs' % (key, m)])])
    return (table(['held-out date', 'method', 'balls', 'recall', 'recall of balls on the field side', 'blob precision'],
                  rows) + '\n\nVerifier time: %.1f µs a candidate (features and score), %.1f candidates a frame.\n\n'
            % (d['pooled.verify_us_per_candidate'], d['pooled.candidates'] / max(1, d['pooled.frames'])) +
            provenance('make eval', 'eval_verifier', d))


def latency():
    d = load('latency')
    rows = []
    for r in d['runs']:
        config, _, repeat = r['label'].partition('#')
        size, _, how = config.partition('@')
        how = {'normal': '`realtime_priority:=0`',
               'overload': 'σ = 60 noise, `colors.txt`, tracker alone, as launched'}.get(how, 'as launched (`realtime_priority` 50)')
        cpu = r['cpu_percent_of_one_core']
        p99 = r.get('window_p99_at_most_ms')
        slowest = ('%s / %s' % (ms(r['tracker_frame_ms_max']), ms(r['tracker_cpu_ms_max']))
                   if 'tracker_frame_ms_max' in r else '')
        rows.append(['%s, %s, run %s' % (size, how, repeat or '1'), r['frames'], ms(r['p50_ms']), ms(r['p99_ms']),
                     ('**≤ %s ms**' % ('%g' % p99)) if p99 is not None else '> 5 ms',
                     '%.2f%%' % r['window_percent_over_ms']['2'] if 'window_percent_over_ms' in r else '',
                     ms(r['max_ms']), slowest, r.get('tracker_frames_over_5ms', ''), r['tracker_drops'],
                     '–' if r['landmark_skips'] is None else r['landmark_skips'],
                     ' / '.join('%.1f' % cpu[n] if n in cpu else '–'
                                for n in ('simulator', 'tracker', 'edge detector', 'landmark'))])
    return (table(['run', 'frames', 'p50 (since start)', 'p99 (since start)', 'p99 over the 60-s window',
                   'window frames over 2 ms', 'max', 'slowest frame in the window: wall-clock / CPU',
                   'frames over 5 ms', 'tracker drops', 'landmark skips',
                   'CPU % of one core: simulator / tracker / edges / landmark'], rows) + '\n\n' +
            provenance('make bench-latency', 'latency', d))


WRITERS = {f.__name__: f for f in (tracker, tracker_noise, tracker_bounded, tracker_noise_ratios, landmark, eval_horizon, eval_no_horizon,
                                   eval_robustness, eval_balls,
                                   eval_balls_bound, eval_field, eval_balls_by_date, eval_verifier, latency)}


def render(text):
    """The README with every figures region rewritten; raises KeyError on an unknown name."""
    return REGION.sub(lambda m: m.group(1) + WRITERS[m.group(2)]() + '\n' + m.group(4), text)


def main():
    parser = argparse.ArgumentParser()
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument('--write', action='store_true')
    mode.add_argument('--check', action='store_true')
    parser.add_argument('--doc', default=os.path.join(ROOT, 'docs', 'performance.md'))
    args = parser.parse_args()
    text = open(args.doc).read()
    try:
        new = render(text)
    except (OSError, KeyError, ValueError) as e:
        print('[figures] cannot write the README tables: %s' % e)
        return 1
    if args.write:
        with open(args.doc, 'w') as f:
            f.write(new)
        print('[figures] wrote %d tables into %s' % (len(REGION.findall(new)), args.doc))
        return 0
    old_regions = {m.group(2): m.group(3) for m in REGION.finditer(text)}
    stale = [name for name, body in ((m.group(2), m.group(3)) for m in REGION.finditer(new)) if old_regions[name] != body]
    for name in stale:
        line = text[:text.index('<!-- figures: %s -->' % name)].count('\n') + 1
        print('[figures] %s:%d: the %s table differs from bench/results (run scripts/readme_figures.py --write)'
              % (os.path.relpath(args.doc, ROOT), line, name))
    print('[figures] %d tables, %d differ from bench/results' % (len(old_regions), len(stale)))
    return 1 if stale else 0


if __name__ == '__main__':
    sys.exit(main())
