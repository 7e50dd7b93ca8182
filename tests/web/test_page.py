#!/usr/bin/env python3
"""The web page's test: drives accelviz.html in headless Chromium over the DevTools protocol.

    python3 tests/web/test_page.py --web-dir build-web/site --cli build/bin/accelviz-cli \
        [--shared ../shared] [--only NAME] [--keep] [-v]

Serves --web-dir on 127.0.0.1 (a free port), writes its viewer scripts into
WEB_DIR/test-scripts/ (removed at the end unless --keep) and opens one page per script.
Prints 'PASS: name (seconds)', 'FAIL: name: why' (details indented below it) or
'SKIP: name: why' per check, then 'N passed, N failed'. Exit 0 when none failed, 1
otherwise, 77 (skipped) when the web folder has no accelviz.html or Chromium is missing, 2
on bad arguments.

Checks (--only takes the short name or the full one; repeatable):
  loads        'loads'               the page alone logs 'accelviz: ready', no error
  hits         'hits match the CLI'  ray-at-pixel + print-hit per structure = accelviz-cli trace
  screenshots  'screenshots'         the five PNGs decode, are 640x480, not blank, all different
  playlist     'playlist'            next/print-state through scenes/lecture.playlist
  bad-obj      'bad OBJ dropped'     a dropped bad OBJ gives one 'file:3:' line, page lives on
  bad-script   'bad script'          an unknown command on line 2 gives 'script failed: ...:2:'
  f12          'F12 downloads a screenshot'  F12 saves accelviz_0001.png, the canvas's size
  blackboard   'blackboard'          the 2D mode: ray2d + print-hit per structure on the bundled
                                     scenes/blackboard.scene2d give its hit (triangle 7 at 13.238)
  on-demand    'files on demand'     a playlist, an OBJ and scripts next to the page, not bundled
                                     and not in the URL's fetch=: ?playlist=...&state=2 reaches
                                     the state that loads the OBJ, ?script= loads it and every
                                     structure's print-hit = accelviz-cli trace, a missing file
                                     and a path out of the folder give their one-line errors
  gif          'GIF recording'       record ... / record stop in the page: the GIF arrives as a
                                     download and decodes (png_check --gif) to its frames
  student      'student structure'   a page built with --student (scripts/build_web.sh): the
                                     student's structure answers as the built-in BVH does, and
                                     `compare` runs it against the built-in of its kind (skipped
                                     when the page has no student structure)
Standard library only.
"""

import argparse
import base64
import collections
import csv
import functools
import http.server
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import traceback
import urllib.parse
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp  # noqa: E402

STRUCTURES = ['grid', 'octree', 'kdtree', 'bvh', 'spheretree']
PAGE_BUNNY = '../shared/scenes/bunny_lowres.obj'  # the bunny as the page sees it
SCRIPTS_DIR = 'test-scripts'
PREFIX = 'accelviz: '
VIEWPORT = (1280, 800)
FATAL = ('exception', 'crash')  # errors that end a wait at once


class CheckFailed(Exception):
    pass


class Skipped(Exception):
    pass


# ---------------------------------------------------------------------------- the server

class QuietHandler(http.server.SimpleHTTPRequestHandler):
    extensions_map = dict(http.server.SimpleHTTPRequestHandler.extensions_map, **{
        '.wasm': 'application/wasm', '.js': 'text/javascript', '.mjs': 'text/javascript',
        '.data': 'application/octet-stream', '.html': 'text/html', '.txt': 'text/plain',
        '.obj': 'text/plain', '.playlist': 'text/plain', '.png': 'image/png',
    })

    def log_message(self, *args):
        pass

    def end_headers(self):
        # No other header: the page must work from any plain static server (no COOP/COEP;
        # it has one thread). The page names no favicon, so a 404 for one would be its bug.
        self.send_header('Cache-Control', 'no-store')
        super().end_headers()


class QuietServer(http.server.ThreadingHTTPServer):
    daemon_threads = True

    def handle_error(self, request, client_address):
        pass  # a browser closing a connection early is not news


def start_server(web_dir):
    handler = functools.partial(QuietHandler, directory=web_dir)
    server = QuietServer(('127.0.0.1', 0), handler)
    thread = threading.Thread(target=server.serve_forever, name='http', daemon=True)
    thread.start()
    return server, thread


# ---------------------------------------------------------------------------- PNG

def decode_png(data):
    """(width, height, rows): rows a list of bytes objects of RGB pixels (alpha dropped).
    8-bit RGB or RGBA, non-interlaced only."""
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise ValueError('not a PNG (bad signature)')
    pos, ihdr, idat = 8, None, []
    while pos + 8 <= len(data):
        length, ctype = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if len(body) != length:
            raise ValueError('truncated %s chunk' % ctype.decode('latin-1'))
        pos += 12 + length
        if ctype == b'IHDR':
            ihdr = struct.unpack('>IIBBBBB', body)
        elif ctype == b'IDAT':
            idat.append(body)
        elif ctype == b'IEND':
            break
    if ihdr is None:
        raise ValueError('no IHDR')
    width, height, depth, colour, _, _, interlace = ihdr
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        raise ValueError('unsupported PNG: depth %d, colour type %d, interlace %d'
                         % (depth, colour, interlace))
    bpp = 3 if colour == 2 else 4
    raw = zlib.decompress(b''.join(idat))
    stride = width * bpp
    if len(raw) != height * (stride + 1):
        raise ValueError('IDAT holds %d bytes, expected %d' % (len(raw), height * (stride + 1)))
    prev = bytearray(stride)
    rows = []
    for y in range(height):
        start = y * (stride + 1)
        ftype = raw[start]
        line = bytearray(raw[start + 1:start + 1 + stride])
        if ftype == 0:
            pass
        elif ftype == 1:  # Sub
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 0xFF
        elif ftype == 2:  # Up
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 0xFF
        elif ftype == 3:  # Average
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif ftype == 4:  # Paeth
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                if pa <= pb and pa <= pc:
                    pred = a
                elif pb <= pc:
                    pred = b
                else:
                    pred = c
                line[i] = (line[i] + pred) & 0xFF
        else:
            raise ValueError('bad filter type %d in row %d' % (ftype, y))
        prev = line
        if bpp == 4:
            rgb = bytearray(width * 3)
            rgb[0::3], rgb[1::3], rgb[2::3] = line[0::4], line[1::4], line[2::4]
            rows.append(bytes(rgb))
        else:
            rows.append(bytes(line))
    return width, height, rows


def pixels(rows):
    """Every pixel as a 3-byte bytes object, row by row."""
    return [row[i:i + 3] for row in rows for i in range(0, len(row), 3)]


# ---------------------------------------------------------------------------- helpers

def accelviz_lines(page, since=0):
    return [t[len(PREFIX):] for t in page.console_lines()[since:] if t.startswith(PREFIX)]


def is_script_end(text):
    """'accelviz: script done' or 'accelviz: script failed'"""
    return text.startswith(PREFIX + 'script done') or text.startswith(PREFIX + 'script failed')


def clip(text, width=300):
    text = text.replace('\n', '\\n')
    return text if len(text) <= width else text[:width] + '... (%d chars)' % len(text)


def parse_float(token):
    try:
        return float.fromhex(token) if 'x' in token.lower() else float(token)
    except ValueError:
        return float(token)


RAY_RE = re.compile(r'^\s*(\S+\s+){5}\S+\s*$')
HIT_RE = re.compile(r'^hit (-?\d+) (\S+)$')


def is_ray_line(text):
    if not RAY_RE.match(text):
        return False
    try:
        [parse_float(t) for t in text.split()]
        return True
    except ValueError:
        return False


def ray_through_centre(obj_path):
    """A ray line from outside the mesh's box straight at its centre (along -z)."""
    lo, hi = [float('inf')] * 3, [float('-inf')] * 3
    with open(obj_path) as f:
        for line in f:
            if line.startswith('v '):
                xyz = [float(v) for v in line.split()[1:4]]
                lo = [min(a, b) for a, b in zip(lo, xyz)]
                hi = [max(a, b) for a, b in zip(hi, xyz)]
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    start = [centre[0], centre[1], hi[2] + (hi[2] - lo[2])]
    return '%.9g %.9g %.9g 0 0 -1' % tuple(start)


def wait_for_downloads(folder, suffix, timeout=30):
    """The names of the files in `folder` ending in `suffix`, once there is one (empty after
    `timeout` seconds), then half a second more for the download's last bytes."""
    deadline = time.monotonic() + timeout
    names = []
    while time.monotonic() < deadline:
        names = sorted(n for n in os.listdir(folder) if n.endswith(suffix))
        if names:
            time.sleep(0.5)
            break
        time.sleep(0.2)
    return names


class Run:
    """A viewer script run in a page: its console lines, errors and how it ended."""

    def __init__(self, name, lines, end, errors, details):
        self.name, self.lines, self.end, self.errors, self.details = (
            name, lines, end, errors, details)


class Tester:
    def __init__(self, args):
        self.args = args
        self.web_dir = os.path.abspath(args.web_dir)
        self.scripts_dir = os.path.join(self.web_dir, SCRIPTS_DIR)
        self.base_url = None
        self._bunny_run = None
        self.passed = self.failed = self.skipped = 0

    # -- pages
    def browser(self):
        return cdp.Browser(self.args.chromium, stderr_path=self.args.chromium_log)

    def url(self, script=None):
        url = self.base_url + '/accelviz.html'
        if script is not None:
            url += '?script=' + urllib.parse.quote(script, safe='/')
        return url

    def write_script(self, name, lines):
        path = os.path.join(self.scripts_dir, name)
        with open(path, 'w') as f:
            f.write('\n'.join(lines) + '\n')
        return SCRIPTS_DIR + '/' + name

    def run_script(self, name, lines, timeout, downloads=None, query=None):
        """Writes and runs a script in a fresh page (with `lines`; None: the page's `query`
        instead, the script already written); returns a Run (end None on a timeout).
        `downloads`: (folder, suffix): the browser saves downloads into the folder, and the
        browser stays open until a file ending in the suffix is there (or 30 s passed):
        closing it earlier cancels a download still being written."""
        script = self.write_script(name, lines) if lines is not None else None
        with self.browser() as browser:
            if downloads:
                browser.send('Browser.setDownloadBehavior', {'behavior': 'allow', 'downloadPath': downloads[0]})
            page = browser.new_page(*VIEWPORT)
            page.navigate(self.url(script) if query is None else self.base_url + '/accelviz.html?' + query)
            end, details = None, ''
            try:
                # An uncaught exception (an emscripten abort) ends the wait early.
                end = page.wait_for_console(is_script_end, timeout=timeout,
                                            fail_on_error=FATAL)
            except cdp.CdpError as e:
                details = str(e)
                try:  # the page may still report the end after the exception
                    end = page.wait_for_console(is_script_end, timeout=2)
                except cdp.CdpError:
                    pass
            time.sleep(0.3)  # late errors
            if downloads and end is not None:
                wait_for_downloads(*downloads)
            if self.args.verbose:
                for level, text in page.console:
                    print('    [%s] %s' % (level, clip(text, 200)))
            return Run(name, accelviz_lines(page), end, list(page.errors),
                       details or page.last_console())

    # -- the checks
    def ready_page(self, browser, fail_on_error):
        """The page without a query, once the viewer logged 'ready'."""
        page = browser.new_page(*VIEWPORT)
        page.navigate(self.url())
        page.wait_for_console(lambda t: t == PREFIX + 'ready', timeout=60,
                              fail_on_error=fail_on_error, what=repr(PREFIX + 'ready'))
        return page

    def check_loads(self):
        with self.browser() as browser:
            page = self.ready_page(browser, fail_on_error=True)
            time.sleep(1.0)  # errors that follow the ready line
            if page.errors:
                src, text = page.errors[0]
                raise CheckFailed('%d error(s) after loading, first [%s] %s\n%s' % (
                    len(page.errors), src, clip(text, 500), page.last_console()))

    def need_bunny(self):
        native = os.path.join(self.args.shared, 'scenes', 'bunny_lowres.obj')
        if not os.path.isfile(native):
            raise Skipped('no %s (--shared)' % native)
        return native

    def bunny_run(self):
        if self._bunny_run is None:
            lines = ['# written by tests/web/test_page.py', 'size 640 480', 'scene ' + PAGE_BUNNY]
            for name in STRUCTURES:
                lines += ['structure ' + name, 'ray-at-pixel 320 240', 'print-ray', 'print-hit',
                          'step end', 'screenshot %s/%s.png' % (SCRIPTS_DIR, name)]
            self._bunny_run = self.run_script('bunny.txt', lines, timeout=180)
        return self._bunny_run

    def need_cli(self):
        cli = self.args.cli
        if not cli or not os.path.isfile(cli) or not os.access(cli, os.X_OK):
            raise CheckFailed('no executable accelviz-cli at %r (--cli)' % cli)
        return cli

    def cli_mismatches(self, native, answers):
        """`answers`: (structure, ray line, page's print-hit line) on the mesh `native`; the
        differences from accelviz-cli trace's answers, one string each."""
        cli = self.need_cli()
        problems = []
        tmp = tempfile.mkdtemp(prefix='accelviz-web-test-')
        try:
            for name, ray, hit in answers:
                m = HIT_RE.match(hit)
                if not m:
                    problems.append('%s: the ray misses (ray %s)' % (name, ray))
                    continue
                prim, t = int(m.group(1)), float(m.group(2))
                rays_file = os.path.join(tmp, name + '.rays')
                out_csv = os.path.join(tmp, name + '.csv')
                with open(rays_file, 'w') as f:
                    f.write(ray.strip() + '\n')
                cmd = [cli, 'trace', '--scene', native, '--structure', name,
                       '--rays', rays_file, '--out', out_csv]
                try:
                    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
                except subprocess.TimeoutExpired:
                    problems.append('%s: accelviz-cli trace took over 300 s' % name)
                    continue
                if proc.returncode != 0:
                    problems.append('%s: accelviz-cli trace exited %d: %s' % (
                        name, proc.returncode, clip(proc.stderr.strip(), 300)))
                    continue
                with open(out_csv, newline='') as f:
                    rows = list(csv.DictReader(f))
                if len(rows) != 1:
                    problems.append('%s: the CLI wrote %d rows, expected 1' % (name, len(rows)))
                    continue
                cli_prim, cli_t = int(rows[0]['prim']), float(rows[0]['t'])
                if cli_prim < 0:
                    problems.append('%s: the page hits %d at %.9g, the CLI misses (ray %s)' % (
                        name, prim, t, ray))
                elif prim != cli_prim or abs(t - cli_t) > 1e-6 * abs(cli_t):
                    problems.append('%s: page hit %d %.9g, CLI hit %d %.9g (ray %s)' % (
                        name, prim, t, cli_prim, cli_t, ray))
                elif self.args.verbose:
                    print('    %s: hit %d %.9g (ray %s)' % (name, prim, t, ray))
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        return problems

    def check_hits(self):
        native = self.need_bunny()
        self.need_cli()
        run = self.bunny_run()
        if run.end is None:
            raise CheckFailed('the script did not end: %s' % run.details)
        if not run.end.startswith(PREFIX + 'script done'):
            raise CheckFailed('%s\n%s' % (run.end, run.details))
        rays = [t for t in run.lines if is_ray_line(t)]
        hits = [t for t in run.lines if HIT_RE.match(t) or t == 'miss']
        if len(rays) != len(STRUCTURES) or len(hits) != len(STRUCTURES):
            raise CheckFailed('expected %d print-ray and %d print-hit lines, got %d and %d\n%s' % (
                len(STRUCTURES), len(STRUCTURES), len(rays), len(hits), run.details))
        problems = self.cli_mismatches(native, list(zip(STRUCTURES, rays, hits)))
        if problems:
            raise CheckFailed('; '.join(problems))

    def check_screenshots(self):
        self.need_bunny()
        run = self.bunny_run()
        shots = {}
        for text in run.lines:
            if text.startswith('screenshot '):
                parts = text.split(' ', 2)
                if len(parts) == 3:
                    shots[parts[1]] = parts[2]
        problems, images = [], {}
        for name in STRUCTURES:
            path = '%s/%s.png' % (SCRIPTS_DIR, name)
            url = shots.get(path)
            if url is None:
                problems.append('%s: no "screenshot %s data:..." line' % (name, path))
                continue
            head = 'data:image/png;base64,'
            if not url.startswith(head):
                problems.append('%s: not a PNG data URL: %s' % (name, clip(url, 60)))
                continue
            try:
                png = base64.b64decode(url[len(head):], validate=True)
                if self.args.keep:
                    with open(os.path.join(self.scripts_dir, name + '.png'), 'wb') as f:
                        f.write(png)
                width, height, rows = decode_png(png)
            except (ValueError, zlib.error, struct.error) as e:
                problems.append('%s: %s' % (name, e))
                continue
            if (width, height) != (640, 480):
                problems.append('%s: %dx%d, expected 640x480' % (name, width, height))
                continue
            px = pixels(rows)
            common, count = collections.Counter(px).most_common(1)[0]
            other = len(px) - count
            if other < 0.01 * len(px):
                problems.append('%s: blank: %d of %d pixels differ from the most common colour '
                                '#%s' % (name, other, len(px), common.hex()))
                continue
            images[name] = px
        names = list(images)
        for i, a in enumerate(names):
            for b in names[i + 1:]:
                diff = sum(1 for p, q in zip(images[a], images[b]) if p != q)
                if diff <= 0.005 * len(images[a]):
                    problems.append('%s and %s: only %d pixels differ' % (a, b, diff))
        if problems:
            if run.end is None or not run.end.startswith(PREFIX + 'script done'):
                end = run.end or 'did not end: ' + run.details.split('\n')[0]
                problems.append('the script: %s' % clip(end))
            raise CheckFailed('; '.join(problems))

    def check_playlist(self):
        steps = 40
        lines = ['# written by tests/web/test_page.py', 'playlist scenes/lecture.playlist',
                 'print-state'] + ['next', 'print-state'] * steps
        run = self.run_script('playlist.txt', lines, timeout=300)
        if run.end is None:
            raise CheckFailed('the script did not end: %s' % run.details)
        if not run.end.startswith(PREFIX + 'script done'):
            raise CheckFailed('%s\n%s' % (run.end, run.details))
        states = []
        for text in run.lines:
            m = re.match(r'^state (\d+)/(\d+)(:|$)', text)
            if m:
                states.append((int(m.group(1)), int(m.group(2))))
            elif text.startswith('state '):
                raise CheckFailed('malformed state line: %s' % clip(text))
        if len(states) != steps + 1:
            raise CheckFailed('%d state lines, expected %d\n%s' % (
                len(states), steps + 1, run.details))
        totals = set(n for _, n in states)
        if len(totals) != 1:
            raise CheckFailed('the state count changes: %s' % sorted(totals))
        n = totals.pop()
        if n < 10:
            raise CheckFailed('only %d states' % n)
        if n > steps:
            raise CheckFailed('%d states, the test expects fewer than %d' % (n, steps))
        ks = [k for k, _ in states]
        expected = [min(i + 1, n) for i in range(steps + 1)]
        if ks != expected:
            first = next(i for i, (a, b) in enumerate(zip(ks, expected)) if a != b)
            raise CheckFailed('state numbers %s..., expected %s... (differ at print-state %d)' % (
                ks[:first + 3], expected[:first + 3], first + 1))
        if run.errors:
            src, text = run.errors[0]
            raise CheckFailed('%d console error(s), first [%s] %s' % (
                len(run.errors), src, clip(text, 500)))

    def check_bad_obj(self):
        with self.browser() as browser:
            page = self.ready_page(browser, fail_on_error=FATAL)
            mark = page.mark()
            errors_before = len(page.errors)
            dispatched = page.evaluate(r"""(() => {
  const canvas = document.querySelector('canvas');
  if (!canvas) throw new Error('no canvas in the page');
  const file = new File(['v 0 0 0\nv 1 0 0\nf 1 2 7\n'], 'bad.obj', {type: 'text/plain'});
  const dt = new DataTransfer();
  dt.items.add(file);
  const r = canvas.getBoundingClientRect();
  const at = {clientX: r.left + r.width / 2, clientY: r.top + r.height / 2};
  const result = {};
  for (const type of ['dragenter', 'dragover', 'drop']) {
    const ev = new DragEvent(type, Object.assign({dataTransfer: dt, bubbles: true,
                                                  cancelable: true, composed: true}, at));
    result[type] = canvas.dispatchEvent(ev) ? 'not cancelled' : 'cancelled';
  }
  return result;
})()""")

            def bad_obj_line(text):
                """'accelviz: ...bad.obj...:3:...'"""
                return text.startswith(PREFIX) and 'bad.obj' in text and ':3:' in text
            try:
                line = page.wait_for_console(bad_obj_line, timeout=20, since=mark,
                                             fail_on_error=FATAL)
            except cdp.CdpError as e:
                raise CheckFailed('%s (dispatchEvent: %s)' % (e, dispatched))
            if '\n' in line or '\r' in line:
                raise CheckFailed('the message spans lines: %r' % clip(line, 400))
            time.sleep(0.5)
            try:
                two = page.evaluate('1+1', timeout=20)
            except cdp.CdpError as e:
                raise CheckFailed('the page no longer answers: %s' % e)
            if two != 2:
                raise CheckFailed('1+1 evaluated to %r' % (two,))
            thrown = [e for e in page.errors[errors_before:] if e[0] in ('exception', 'crash')]
            if thrown:
                raise CheckFailed('an exception after the drop: %s' % clip(thrown[0][1], 500))
            if self.args.verbose:
                print('    %s' % line)

    def check_bad_script(self):
        run = self.run_script('bad-script.txt', [
            'size 640 480', 'frobnicate-the-widget 1 2 3', 'print-state'], timeout=30)
        if run.end is None:
            raise CheckFailed('no "script failed": %s' % run.details)
        if not run.end.startswith(PREFIX + 'script failed: '):
            raise CheckFailed('expected "script failed: ...:2: ...", got %s' % clip(run.end))
        if ':2:' not in run.end:
            raise CheckFailed('the message does not name line 2 (":2:"): %s' % clip(run.end))
        if '\n' in run.end:
            raise CheckFailed('the message spans lines: %r' % clip(run.end))

    def check_f12(self):
        """F12 in the page: the screenshot arrives as a downloaded PNG of the canvas."""
        downloads = tempfile.mkdtemp(prefix='accelviz-downloads-')
        try:
            with self.browser() as browser:
                browser.send('Browser.setDownloadBehavior', {'behavior': 'allow', 'downloadPath': downloads})
                page = self.ready_page(browser, fail_on_error=FATAL)
                page.press_key('F12')
                names = wait_for_downloads(downloads, '.png')
                if names != ['accelviz_0001.png']:
                    raise CheckFailed('expected accelviz_0001.png downloaded within 30 s, got %s\n%s' % (
                        names, page.last_console()))
                with open(os.path.join(downloads, names[0]), 'rb') as f:
                    width, height, _ = decode_png(f.read())
                if (width, height) != VIEWPORT:
                    raise CheckFailed('the PNG is %dx%d, the page %dx%d' % (width, height, *VIEWPORT))
        finally:
            shutil.rmtree(downloads, ignore_errors=True)

    def check_blackboard(self):
        # The lecture's ten triangles and its ray (scenes/lecture.playlist): every structure,
        # traversed in the plane, finds triangle 7 at t = 13.238 as the native viewer does.
        lines = ['# written by tests/web/test_page.py', 'size 640 480', 'mode 2d', 'scene2d scenes/blackboard.scene2d']
        for name in STRUCTURES:
            lines += ['structure ' + name, 'ray2d 0.5 4.2 1 0.1', 'print-hit']
        run = self.run_script('blackboard.txt', lines, timeout=120)
        if run.end is None or not run.end.startswith(PREFIX + 'script done'):
            raise CheckFailed('%s\n%s' % (run.end or 'the script did not end', run.details))
        hits = [t for t in run.lines if HIT_RE.match(t) or t == 'miss']
        expected = ['hit 7 13.2380953'] * len(STRUCTURES)
        if hits != expected:
            raise CheckFailed('print-hit gave %s, expected %s' % (hits, expected))

    def check_student(self):
        # A student's structure built into the page (--student-structure, the worked example
        # by default): the same answers as the built-in BVH on fixed rays through the Cornell
        # box, and compare's line against the built-in of its kind.
        name = self.args.student_structure
        rays = ['ray 0 0.5 3 0 0 -1', 'ray 0.3 1.7 2.5 -0.1 -0.4 -1', 'ray -0.9 0.2 -0.4 1 0.3 0.2',
                'ray 0.5 1.9 0 0 -1 0.01', 'ray 0 1 0 0.3 0.2 1']
        lines = ['# written by tests/web/test_page.py', 'size 640 480', 'scene procedural:cornell']
        for structure in (name, 'bvh'):
            lines.append('structure ' + structure)
            for r in rays:
                lines += [r, 'print-hit']
        lines += ['structure ' + name, rays[0], 'compare']
        run = self.run_script('student.txt', lines, timeout=180)
        if run.end is None:
            raise CheckFailed('the script did not end: %s' % run.details)
        if 'unknown structure' in run.end:
            raise Skipped('the page has no structure %r (build it with scripts/build_web.sh --student DIR)' % name)
        if not run.end.startswith(PREFIX + 'script done'):
            raise CheckFailed('%s\n%s' % (run.end, run.details))
        hits = [t for t in run.lines if HIT_RE.match(t) or t == 'miss']
        if len(hits) != 2 * len(rays):
            raise CheckFailed('expected %d print-hit lines, got %s' % (2 * len(rays), hits))
        mine, builtin = hits[:len(rays)], hits[len(rays):]
        if mine != builtin:
            raise CheckFailed('%s answered %s, the built-in bvh %s' % (name, mine, builtin))
        if not any(t.startswith('compare-builtin first difference') or t.startswith('compare-builtin no difference')
                   for t in run.lines):
            raise CheckFailed('compare printed no line against the built-in:\n%s' % '\n'.join(run.lines[-12:]))

    def check_on_demand(self):
        """A lecturer's files next to the page: a playlist, an OBJ and scripts that the page
        does not bundle and the URL does not list (no fetch=). Each is fetched where the
        viewer opens it, however deep the reference: the playlist names the OBJ."""
        native = self.need_bunny()
        self.need_cli()
        course = SCRIPTS_DIR + '/course'  # as the page sees it
        folder = os.path.join(self.web_dir, course)
        os.makedirs(os.path.join(folder, 'meshes'), exist_ok=True)
        shutil.copyfile(native, os.path.join(folder, 'meshes', 'mymesh.obj'))
        ray = ray_through_centre(native)
        # The playlist's paths are relative to it; the scripts' to the page's folder.
        with open(os.path.join(folder, 'course.playlist'), 'w') as f:
            f.write('state One: the Cornell box\nscene procedural:cornell\n\n'
                    'state Two: my own mesh\nscene meshes/mymesh.obj\nstructure kdtree\n'
                    'ray %s\nprint-hit\n' % ray)
        problems = []
        with self.browser() as browser:
            page = browser.new_page(*VIEWPORT)
            page.navigate(self.base_url + '/accelviz.html?playlist=%s/course.playlist&state=2' % course)
            try:
                hit = page.wait_for_console(lambda t: t.startswith(PREFIX) and (
                    HIT_RE.match(t[len(PREFIX):]) or t == PREFIX + 'miss'), timeout=120,
                    fail_on_error=FATAL, what='the state\'s print-hit')
                problems += ['playlist: ' + p for p in self.cli_mismatches(
                    native, [('kdtree', ray, hit[len(PREFIX):])])]
            except cdp.CdpError as e:
                problems.append('playlist: state 2 printed no hit: %s\n%s' % (e, page.last_console()))
        lines = ['size 640 480', 'scene %s/meshes/mymesh.obj' % course]
        for name in STRUCTURES:
            lines += ['structure ' + name, 'ray ' + ray, 'print-hit']
        self.write_script('course/demo.script', lines)
        run = self.run_script('course/demo.script', None, timeout=180,
                              query='script=%s/demo.script' % course)
        if run.end is None or not run.end.startswith(PREFIX + 'script done'):
            problems.append('script: %s' % clip(run.end or run.details))
        else:
            hits = [t for t in run.lines if HIT_RE.match(t) or t == 'miss']
            if len(hits) != len(STRUCTURES):
                problems.append('script: %d print-hit lines, expected %d' % (len(hits), len(STRUCTURES)))
            else:
                problems += ['script: ' + p for p in self.cli_mismatches(
                    native, [(name, ray, hit) for name, hit in zip(STRUCTURES, hits)])]
        # A missing file, and a path out of the page's folder: one line each, naming the
        # file (and the URL tried); the page lives on.
        for name, target, expect in [('missing.script', course + '/meshes/missing.obj', 'the server answered 404'),
                                     ('outside.script', '../outside.obj', 'outside the page\'s folder'),
                                     # a URL of another server: past the path check, refused
                                     # where the browser resolves the URL
                                     ('url.script', 'http://127.0.0.1:9/outside.obj', 'outside the page\'s folder')]:
            run = self.run_script('course/' + name, ['size 640 480', 'scene ' + target], timeout=60)
            end = run.end or ''
            want = PREFIX + 'script failed: %s/%s:2: %s: cannot open (' % (course, name, target)
            if not end.startswith(want) or expect not in end or '\n' in end:
                problems.append('%s: expected "%s... %s ...)" on one line, got %s' % (
                    name, want, expect, clip(end or run.details)))
            elif expect.startswith('the server') and self.base_url + '/' + target not in end:
                problems.append('%s: the message does not name the URL tried: %s' % (name, clip(end)))
            fatal = [e for e in run.errors if e[0] in FATAL]
            if fatal:
                problems.append('%s: the page stopped: [%s] %s' % (name, fatal[0][0], clip(fatal[0][1])))
        if problems:
            raise CheckFailed('; '.join(problems))

    def check_gif(self):
        """`record NAME.gif` ... `record stop` in the page: the desktop's GIF writer, the file
        saved as a download, decoding (stb_image, png_check --gif) to one frame per step."""
        png_check = self.args.png_check
        if not png_check or not os.access(png_check, os.X_OK):
            raise CheckFailed('no executable png_check at %r (--png-check)' % png_check)
        downloads = tempfile.mkdtemp(prefix='accelviz-downloads-')
        try:
            lines = ['size 640 480', 'scene procedural:cornell', 'structure kdtree', 'ray 0 0.5 3 0 0 -1',
                     'step start', 'record clip.gif fps=5 size=320x240', 'step 5', 'record stop']
            run = self.run_script('gif.txt', lines, timeout=120, downloads=(downloads, '.gif'))
            if run.end is None or not run.end.startswith(PREFIX + 'script done'):
                raise CheckFailed('the script: %s' % clip(run.end or run.details))
            wrote = [t for t in run.lines if t.startswith('wrote ')]
            if wrote != ['wrote /app/clip.gif (6 frames)']:
                raise CheckFailed('expected "wrote /app/clip.gif (6 frames)", got %s' % wrote)
            path = os.path.join(downloads, 'clip.gif')
            if wait_for_downloads(downloads, '.gif') != ['clip.gif']:
                raise CheckFailed('no clip.gif downloaded within 30 s (got %s)' % os.listdir(downloads))
            proc = subprocess.run([png_check, '--gif', path, '6', '320', '240'], capture_output=True, text=True)
            if proc.returncode != 0:
                raise CheckFailed('the GIF: %s' % (proc.stderr.strip() or proc.stdout.strip()))
            if self.args.verbose:
                print('    ' + proc.stdout.strip())
        finally:
            shutil.rmtree(downloads, ignore_errors=True)

    CHECKS = [
        ('loads', 'loads', check_loads),
        ('hits', 'hits match the CLI', check_hits),
        ('screenshots', 'screenshots', check_screenshots),
        ('playlist', 'playlist', check_playlist),
        ('bad-obj', 'bad OBJ dropped', check_bad_obj),
        ('bad-script', 'bad script', check_bad_script),
        ('f12', 'F12 downloads a screenshot', check_f12),
        ('blackboard', 'blackboard', check_blackboard),
        ('on-demand', 'files on demand', check_on_demand),
        ('gif', 'GIF recording', check_gif),
        ('student', 'student structure', check_student),
    ]

    def run_checks(self, only):
        for short, name, fn in self.CHECKS:
            if only and short not in only and name not in only:
                continue
            t0 = time.monotonic()
            try:
                fn(self)
            except Skipped as e:
                self.skipped += 1
                print('SKIP: %s: %s' % (name, e), flush=True)
                continue
            except CheckFailed as e:
                self.report_fail(name, str(e))
            except cdp.CdpError as e:
                self.report_fail(name, str(e))
            except Exception:
                self.report_fail(name, traceback.format_exc().rstrip())
            else:
                self.passed += 1
                # The time too: the CI log shows where the browser test's minutes go.
                print('PASS: %s (%.1f s)' % (name, time.monotonic() - t0), flush=True)

    def report_fail(self, name, why):
        self.failed += 1
        first, _, rest = why.partition('\n')
        print('FAIL: %s: %s' % (name, first), flush=True)
        if rest:
            print('\n'.join('    ' + line for line in rest.split('\n')), flush=True)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.dirname(os.path.dirname(here))
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--web-dir', required=True, help='the folder with accelviz.html')
    ap.add_argument('--cli', help='accelviz-cli, for the hits check')
    ap.add_argument('--shared', default=os.path.join(repo, '..', 'shared'),
                    help='the shared folder (scenes/bunny_lowres.obj); default REPO/../shared')
    ap.add_argument('--chromium', default=None, help='the browser (default: chromium on PATH, '
                    'or $CHROMIUM)')
    ap.add_argument('--chromium-log', default=None, help='append chromium\'s stderr here')
    ap.add_argument('--only', action='append', default=[],
                    help='run only this check (repeatable): ' +
                    ', '.join(short for short, _, _ in Tester.CHECKS))
    ap.add_argument('--keep', action='store_true',
                    help='keep WEB_DIR/test-scripts (scripts and the screenshots as PNGs)')
    ap.add_argument('-v', '--verbose', action='store_true', help='print the pages\' console')
    ap.add_argument('--png-check', default=None,
                    help='png_check, for the GIF check (default: next to --cli)')
    ap.add_argument('--student-structure', default='median_bvh',
                    help='the student structure the page was built with (scripts/build_web.sh --student)')
    args = ap.parse_args()

    known = set(s for s, _, _ in Tester.CHECKS) | set(n for _, n, _ in Tester.CHECKS)
    bad = [o for o in args.only if o not in known]
    if bad:
        ap.error('unknown check %s (known: %s)' % (
            ', '.join(bad), ', '.join(s for s, _, _ in Tester.CHECKS)))
    if not os.path.isfile(os.path.join(args.web_dir, 'accelviz.html')):
        print('SKIP: no accelviz.html in %s' % args.web_dir)
        return 77
    args.chromium = args.chromium or cdp.find_chromium()
    if not args.chromium or not shutil.which(args.chromium):
        print('SKIP: chromium not found (--chromium or $CHROMIUM)')
        return 77
    if args.cli:
        args.cli = os.path.abspath(args.cli)
        if args.png_check is None:
            args.png_check = os.path.join(os.path.dirname(args.cli), 'png_check')
    args.shared = os.path.abspath(args.shared)

    tester = Tester(args)
    shutil.rmtree(tester.scripts_dir, ignore_errors=True)
    os.makedirs(tester.scripts_dir)
    server, thread = start_server(tester.web_dir)
    try:
        tester.base_url = 'http://127.0.0.1:%d' % server.server_address[1]
        tester.run_checks(args.only)
    except KeyboardInterrupt:
        print('interrupted')
        tester.failed += 1
    finally:
        server.shutdown()
        server.server_close()
        thread.join(timeout=5)
        if args.keep:
            print('kept %s' % tester.scripts_dir)
        else:
            shutil.rmtree(tester.scripts_dir, ignore_errors=True)
    print('%d passed, %d failed' % (tester.passed, tester.failed))
    return 0 if tester.failed == 0 else 1


if __name__ == '__main__':
    sys.exit(main())
