#!/usr/bin/env python3
"""Every Markdown link of the repository's documents points at a file that exists, and at a
heading that exists when it names one (#anchor, as GitHub makes them).

    python3 tests/docs/check_links.py [REPO]

Checks README.md, bench/README.md, scenes/README.md, student/README.md and docs/*.md: links and images, inline
(`[text](target)`), relative paths only (http(s) and mailto links are not followed). Prints
one line per broken link, 'FILE:LINE: target: why', and exits 1 when there is any.
"""
import os
import re
import sys

LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^()\s]+)(?:\s+"[^"]*")?\)')
HEADING = re.compile(r'^(#{1,6})\s+(.*?)\s*#*\s*$')
FENCE = re.compile(r'^\s*(```|~~~)')


def anchor(title):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    title = re.sub(r'`([^`]*)`', r'\1', title)                 # code spans keep their text
    title = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', title)     # links keep their text
    title = title.strip().lower()
    title = re.sub(r'[^\w\- ]', '', title)
    return title.replace(' ', '-')


def headings(path, cache={}):
    if path not in cache:
        found, seen, fenced = set(), {}, False
        with open(path, encoding='utf-8') as f:
            for line in f:
                if FENCE.match(line):
                    fenced = not fenced
                    continue
                m = None if fenced else HEADING.match(line)
                if m:
                    a = anchor(m.group(2))
                    n = seen.get(a, 0)
                    found.add(a if n == 0 else f'{a}-{n}')  # repeated titles get -1, -2, ...
                    seen[a] = n + 1
        cache[path] = found
    return cache[path]


def check(repo, doc):
    problems = []
    path = os.path.join(repo, doc)
    fenced = False
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced:
                continue
            for m in LINK.finditer(re.sub(r'`[^`]*`', '', line)):
                target = m.group(1)
                if re.match(r'^[a-z]+:', target):
                    continue
                file_part, _, frag = target.partition('#')
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
                where = f'{doc}:{number}: {target}'
                if not os.path.exists(resolved):
                    problems.append(f'{where}: no such file {os.path.relpath(resolved, repo)}')
                elif frag and resolved.endswith('.md') and frag not in headings(resolved):
                    problems.append(f'{where}: no heading with anchor #{frag} in {os.path.relpath(resolved, repo)}')
    return problems


def main():
    repo = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..'))
    docs = ['README.md', 'bench/README.md', 'scenes/README.md', 'student/README.md']
    docs += sorted(os.path.join('docs', n) for n in os.listdir(os.path.join(repo, 'docs')) if n.endswith('.md'))
    problems = []
    for doc in docs:
        if os.path.exists(os.path.join(repo, doc)):
            problems += check(repo, doc)
    for p in problems:
        print(p)
    print(f'{len(docs)} documents, {len(problems)} broken links')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
