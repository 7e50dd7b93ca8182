#!/usr/bin/env python3
"""The source tree keeps the shape the project set itself (issue #29):

  * no source file in core/ or app/ is over 700 lines (one lecture algorithm per file);
  * nothing in app/ compares a structure's name to a literal: what a front end needs of a
    structure comes from its registry entry (core/registry.h).

    python3 tests/source/check_sources.py [REPO]

Prints one line per offence, 'FILE:LINE: why', and exits 1 when there is any.
"""
import os
import re
import sys

MAX_LINES = 700
SOURCE = re.compile(r'\.(cpp|h|hpp|cc)$')


def structure_names(repo):
    """The registered names, read from core/registry.cpp's entries."""
    text = open(os.path.join(repo, 'core', 'registry.cpp'), encoding='utf-8').read()
    return re.findall(r'^\s*\{"([a-z_]+)",', text, re.M)


def main():
    repo = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), '..', '..'))
    names = structure_names(repo)
    if len(names) < 6:
        print(f'{repo}/core/registry.cpp: found only {names} as registered structures')
        return 1
    alternatives = '|'.join(map(re.escape, names))
    compare = re.compile(rf'(==|!=)\s*"({alternatives})"|"({alternatives})"\s*(==|!=)')
    problems = []
    for top in ('core', 'app'):
        for folder, _, files in os.walk(os.path.join(repo, top)):
            for name in sorted(files):
                if not SOURCE.search(name):
                    continue
                path = os.path.join(folder, name)
                rel = os.path.relpath(path, repo)
                lines = open(path, encoding='utf-8').read().split('\n')
                count = len(lines) - (1 if lines and lines[-1] == '' else 0)
                if count > MAX_LINES:
                    problems.append(f'{rel}:{count}: {count} lines, over the {MAX_LINES}-line ceiling')
                if top == 'app':
                    for number, line in enumerate(lines, 1):
                        if compare.search(line.split('//')[0]):
                            problems.append(f'{rel}:{number}: compares a structure name to a literal '
                                            '(take it from the registry entry)')
    for p in problems:
        print(p)
    print(f'{len(names)} structures, {len(problems)} problems', file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
