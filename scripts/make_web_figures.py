#!/usr/bin/env python3
"""The web page's figures of docs/viewer.md: the page in headless Chromium, as a visitor sees it.

    python3 scripts/make_web_figures.py [--web-dir build-web] [--out bench/figures]

Writes web_lecture.png (the lecture playlist opened at a state by its URL) and web_bunny.png
(the bunny's kd-tree from the URL, a ray shot by a click into the view, stepped with the
keyboard). Build the page first (scripts/build_web.sh).
"""
import argparse
import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
repo = os.path.dirname(here)
sys.path.insert(0, os.path.join(repo, 'tests', 'web'))
import cdp  # noqa: E402
import test_page  # noqa: E402  (its static file server)

SIZE = (1280, 720)


def wait_until(page, js, timeout=120):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if page.evaluate(js):
            return
        time.sleep(0.2)
    raise RuntimeError(f'timed out waiting for {js}; title: {page.evaluate("document.title")}')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--web-dir', default=os.path.join(repo, 'build-web'))
    ap.add_argument('--out', default=os.path.join(repo, 'bench', 'figures'))
    args = ap.parse_args()
    server, _ = test_page.start_server(args.web_dir)
    base = f'http://127.0.0.1:{server.server_address[1]}/accelviz.html'
    os.makedirs(args.out, exist_ok=True)
    try:
        with cdp.Browser() as browser:
            page = browser.new_page(*SIZE)
            # A slide's link: the lecture at its kd-tree state, tree diagram open.
            page.navigate(base + '?playlist=lecture&state=16')
            page.wait_for_console('accelviz: ready', timeout=120)
            wait_until(page, "document.title.includes('state 8/') && !document.title.includes('loading')")
            time.sleep(3)  # the state's title fades in the view
            with open(os.path.join(args.out, 'web_lecture.png'), 'wb') as f:
                f.write(page.screenshot_png())
            # A mesh by name, a structure and a parameter from the URL; then the mouse and keys.
            page.navigate(base + '?scene=bunny&structure=kdtree&param=leaf_size=2')
            page.wait_for_console('accelviz: ready', timeout=120)
            wait_until(page, "document.title.includes('kdtree')")
            time.sleep(1)
            page.click(SIZE[0] // 2 + 10, SIZE[1] // 2 + 40)  # into the bunny
            time.sleep(2)
            for _ in range(12):
                page.press_key('ArrowRight')
                time.sleep(0.3)
            time.sleep(1)
            with open(os.path.join(args.out, 'web_bunny.png'), 'wb') as f:
                f.write(page.screenshot_png())
    finally:
        server.shutdown()
    print('wrote web_lecture.png and web_bunny.png to', args.out)


if __name__ == '__main__':
    main()
