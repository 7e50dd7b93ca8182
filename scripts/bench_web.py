#!/usr/bin/env python3
"""The web page against the native viewer on one thread: the same viewer script in both.

    python3 scripts/bench_web.py --web-dir build-web --viewer build/bin/accelviz \
        --shared ../shared --out-md bench/web.md --out-json bench/web.json

Measures, on this machine:
  * page load to first frame (navigation start to the first animation frame after the
    viewer printed 'ready'), and the native viewer's start to its first frame;
  * the frame time with the bunny (69,451 triangles) and its BVH drawn (print-frame-time);
  * the viewer's default BVH build (bvh width=2) of the bunny, at first use and warm, and
    of crytek_sponza (print-stats' build_ms);
  * 100,000 random rays through that BVH (trace-rays random:100000:1, one thread), likewise;
  * the page's size (every file a browser downloads).
The native viewer runs under xvfb-run pinned to one core (taskset -c 0: TBB then builds on
one thread, as the page must); Chromium renders with SwiftShader, the native viewer with
Mesa's llvmpipe: both on the CPU, so the frame times compare renderers as much as builds.
Each figure is the median of --runs runs.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(here), 'tests', 'web'))
import cdp  # noqa: E402
import test_page  # noqa: E402  (its static file server)

# The page's first runs use the browser's baseline code (Liftoff); the optimised code
# replaces it function by function as they get hot. So the bunny is timed first ("first
# use"), and again after the sponza ("warm"). Builds and rays are timed with a small window
# and nothing drawn: Chromium draws with SwiftShader on the same two cores, which would time
# the renderer too. The frame time comes last, at full size with the mesh and the BVH drawn.
SCRIPT = """size 320 240
mesh off
nodes off
scene ../shared/scenes/bunny.obj
print-stats
trace-rays random:100000:1
scene {sponza}
print-stats
trace-rays random:100000:1
scene ../shared/scenes/bunny.obj
print-stats
trace-rays random:100000:1
size 1280 720
mesh solid
nodes on
print-frame-time 20
"""
PAGE_FILES = ['accelviz.html', 'page.js', 'accelviz.js', 'accelviz.wasm', 'accelviz.data']


def parse_output(lines):
    """print-stats / print-frame-time / trace-rays lines -> figures, in script order."""
    out = {'build_ms': [], 'frame_ms': [], 'trace_ms': [], 'hits': []}
    for line in lines:
        if m := re.search(r'^stats .* build_ms ([0-9.]+)', line):
            out['build_ms'].append(float(m.group(1)))
        elif m := re.search(r'^frame-time ([0-9.]+) ms', line):
            out['frame_ms'].append(float(m.group(1)))
        elif m := re.search(r'^trace-rays \S+: (\d+) rays, (\d+) hits, ([0-9.]+) ms', line):
            out['hits'].append(int(m.group(2)))
            out['trace_ms'].append(float(m.group(3)))
    # build_ms and trace_ms: [bunny first use, sponza, bunny warm].
    if len(out['build_ms']) != 3 or len(out['frame_ms']) != 1 or len(out['trace_ms']) != 3:
        raise RuntimeError('unexpected script output:\n' + '\n'.join(lines[-20:]))
    return out


def run_native(viewer, repo):
    script = os.path.join(repo, 'build', 'bench_web_native.txt')
    with open(script, 'w') as f:
        f.write(SCRIPT.format(sponza='../shared/scenes/crytek_sponza.obj'))
    cmd = ['taskset', '-c', '0', 'xvfb-run', '-a', '-s', '-screen 0 1280x720x24', viewer, '--script', script]
    p = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, timeout=900)
    if p.returncode != 0:
        raise RuntimeError('native viewer failed: ' + p.stderr[-2000:])
    out = parse_output(p.stdout.splitlines())
    # Start to first frame: the wall time of a screenshot after one frame, on one core.
    start = time.perf_counter()
    subprocess.run(['taskset', '-c', '0', 'xvfb-run', '-a', viewer, '--frames', '1', '--screenshot',
                    os.path.join(repo, 'build', 'bench_web_first.png')], cwd=repo, check=True,
                   capture_output=True, timeout=300)
    out['first_frame_ms'] = 1000.0 * (time.perf_counter() - start)
    return out


def run_web(web_dir, shared):
    stage = os.path.join(web_dir, 'bench-scenes')
    os.makedirs(stage, exist_ok=True)
    shutil.copy(os.path.join(shared, 'scenes', 'crytek_sponza.obj'), stage)
    with open(os.path.join(stage, 'bench.txt'), 'w') as f:
        f.write(SCRIPT.format(sponza='bench-scenes/crytek_sponza.obj'))
    server, _ = test_page.start_server(web_dir)
    port = server.server_address[1]
    try:
        with cdp.Browser() as browser:
            page = browser.new_page(1280, 720)
            page.navigate(f'http://127.0.0.1:{port}/accelviz.html')
            page.wait_for_console('accelviz: ready', timeout=120)
            deadline = time.time() + 30
            first = None
            while first is None and time.time() < deadline:
                first = page.evaluate('window.accelvizFirstFrameMs || null')
                time.sleep(0.05)
            page.navigate(f'http://127.0.0.1:{port}/accelviz.html?script=bench-scenes/bench.txt'
                          '&fetch=bench-scenes/crytek_sponza.obj')
            page.wait_for_console('accelviz: script done', timeout=900, fail_on_error=True)
            lines = [text[len('accelviz: '):] for text in page.console_lines() if text.startswith('accelviz: ')]
    finally:
        server.shutdown()
        shutil.rmtree(stage, ignore_errors=True)
    out = parse_output(lines)
    out['first_frame_ms'] = first
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--web-dir', required=True)
    ap.add_argument('--viewer', required=True)
    ap.add_argument('--shared', required=True)
    ap.add_argument('--runs', type=int, default=3)
    ap.add_argument('--out-md', required=True)
    ap.add_argument('--out-json', required=True)
    args = ap.parse_args()
    repo = os.path.dirname(here)
    runs = {'web': [], 'native': []}
    for i in range(args.runs):
        runs['web'].append(run_web(args.web_dir, args.shared))
        runs['native'].append(run_native(os.path.abspath(args.viewer), repo))
        print(f'run {i + 1}: web {runs["web"][-1]}, native {runs["native"][-1]}', file=sys.stderr)

    def median(side, key, index=None):
        values = [r[key] if index is None else r[key][index] for r in runs[side]]
        return statistics.median(values)

    rows = [
        ('page load / start to first frame (ms)', 'first_frame_ms', None),
        ('frame time, bunny and its BVH drawn (ms)', 'frame_ms', 0),
        ('default BVH build, bunny, 69,451 triangles, first use (ms)', 'build_ms', 0),
        ('default BVH build, bunny, warm (ms)', 'build_ms', 2),
        ('default BVH build, crytek_sponza, 262,267 triangles (ms)', 'build_ms', 1),
        ('100,000 random rays, bunny BVH, one thread, first use (ms)', 'trace_ms', 0),
        ('100,000 random rays, bunny BVH, one thread, warm (ms)', 'trace_ms', 2),
        ('100,000 random rays, crytek_sponza BVH, one thread (ms)', 'trace_ms', 1),
    ]
    table = []
    for label, key, index in rows:
        w, n = median('web', key, index), median('native', key, index)
        table.append({'what': label, 'web': w, 'native': n, 'ratio': w / n if n else None})
    same_hits = all(r['hits'] == runs['native'][0]['hits'] for r in runs['web'] + runs['native'])
    size = sum(os.path.getsize(os.path.join(args.web_dir, f)) for f in PAGE_FILES)
    sizes = {f: os.path.getsize(os.path.join(args.web_dir, f)) for f in PAGE_FILES}
    result = {'date': time.strftime('%Y-%m-%d'), 'runs': args.runs, 'rows': table, 'same_hits': same_hits,
              'hits': runs['native'][0]['hits'], 'page_bytes': size, 'page_files': sizes,
              'machine': f'{os.cpu_count()} cores', 'raw': runs}
    with open(args.out_json, 'w') as f:
        json.dump(result, f, indent=1)
    with open(args.out_md, 'w') as f:
        f.write('# The web page against the native viewer on one thread\n\n')
        f.write(f'`scripts/bench_web.sh` on {result["date"]}, this {os.cpu_count()}-core machine, median of '
                f'{args.runs} runs. The same viewer script in both (`SCRIPT` in scripts/bench_web.py); '
                'the page in headless Chromium (SwiftShader WebGL2), the native viewer under xvfb-run '
                '(Mesa llvmpipe) pinned to one core.\n\n')
        f.write('| | web | native, 1 core | web / native |\n|---|---:|---:|---:|\n')
        for r in table:
            f.write(f'| {r["what"]} | {r["web"]:.1f} | {r["native"]:.1f} | {r["ratio"]:.2f}x |\n')
        f.write(f'\nThe same hits in both: {"yes" if same_hits else "NO"} '
                f'({result["hits"][0]:,} and {result["hits"][1]:,} of 100,000).\n\n')
        f.write(f'The page: {size / 1e6:.1f} MB in all (' +
                ', '.join(f'`{k}` {v / 1e6:.2f} MB' for k, v in sizes.items()) + ').\n')
    print(open(args.out_md).read())


if __name__ == '__main__':
    main()
