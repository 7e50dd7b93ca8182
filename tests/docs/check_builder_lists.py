#!/usr/bin/env python3
"""The BVH builder lists of README.md and docs/structures.md are the builder table's.

The table (core/structures/bvh_builders.cpp) names every builder once; `accelviz-cli params`
prints them as the `builder` parameter's choices, the default first. The documents write the
same list as `builder=DEFAULT\\|...` (and README counts them in words). This test fails,
printing what differs, when a builder was added, renamed or removed on one side only;
--write rewrites the lists from the table instead.

    python3 tests/docs/check_builder_lists.py --cli build/bin/accelviz-cli [--repo .] [--write]
"""
import argparse
import os
import re
import subprocess
import sys

DOCUMENTS = ['README.md', 'docs/structures.md']
LIST = re.compile(r'builder=[a-z_]+(?:\\\|[a-z_]+)+')
WORDS = ['zero', 'one', 'two', 'three', 'four', 'five', 'six', 'seven', 'eight', 'nine', 'ten', 'eleven', 'twelve']


def table(cli):
    """The bvh builder choices, the default first, as `accelviz-cli params` prints them."""
    out = subprocess.run([cli, 'params'], capture_output=True, text=True, check=True).stdout
    in_bvh = False
    for line in out.splitlines():
        if not line.startswith(' '):
            in_bvh = line.startswith('bvh:')
            continue
        m = re.match(r'\s+builder\s+default (\S+)\s+one of: ([a-z_, ]+);', line)
        if in_bvh and m:
            names = [n.strip() for n in m.group(2).split(',')]
            return [m.group(1)] + [n for n in names if n != m.group(1)]
    sys.exit('check_builder_lists: no bvh builder line in `accelviz-cli params`')


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--cli', required=True)
    ap.add_argument('--repo', default='.')
    ap.add_argument('--write', action='store_true')
    args = ap.parse_args()
    names = table(args.cli)
    wanted = 'builder=' + '\\|'.join(names)
    count = '%s builders' % WORDS[len(names)] if len(names) < len(WORDS) else '%d builders' % len(names)
    problems = []
    for doc in DOCUMENTS:
        path = os.path.join(args.repo, doc)
        text = open(path).read()
        found = LIST.findall(text)
        if not found:
            problems.append('%s: no `builder=...` list' % doc)
        new = LIST.sub(lambda m: wanted, text)
        if doc == 'README.md':
            new = re.sub(r'\b(\w+) builders \(', lambda m: count + ' (', new, count=1)
        if new != text:
            if args.write:
                open(path, 'w').write(new)
                print('%s: rewrote the builder list' % doc)
            else:
                problems.append('%s: %s, the table gives %s (%s)' % (doc, sorted(set(found)), wanted, count))
    for p in problems:
        print(p)
    if not problems:
        print('the builder lists match the table: %s' % ', '.join(names))
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
