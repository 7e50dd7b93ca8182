#!/usr/bin/env python3
"""The keys and script tables of the documents are the ones the viewer's rows make.

Each tool declares its keys and script verbs as rows (app/viewer/commands.h), the mouse its
rows per mode (app/viewer/input.h); `accelviz --list keys|keys-summary|commands|mouse` prints
them as Markdown tables. This test compares each
table with the block of the document that holds it, between the lines

    <!-- generated: accelviz --list WHAT -->
    <!-- end of generated table -->

and fails, printing the difference, when a row was added, changed or removed on one side
only. --write rewrites the blocks from the viewer instead.

    python3 tests/app/test_docs_tables.py --viewer build/bin/accelviz [--repo .] [--write]

Needs no display: --list answers before any window opens.
"""
import argparse
import difflib
import os
import re
import subprocess
import sys

# document -> the tables it holds
DOCUMENTS = {
    'docs/viewer.md': ['mouse', 'keys', 'commands'],
    'README.md': ['keys-summary'],
}
END = '<!-- end of generated table -->'


def block_pattern(what):
    return re.compile(r'(<!-- generated: accelviz --list ' + re.escape(what) + r' -->\n)(.*?)(' + re.escape(END) + ')',
                      re.S)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--viewer', required=True)
    parser.add_argument('--repo', default=os.path.join(os.path.dirname(__file__), '..', '..'))
    parser.add_argument('--write', action='store_true', help='rewrite the documents\' tables from the viewer')
    args = parser.parse_args()

    problems = 0
    for doc, tables in DOCUMENTS.items():
        path = os.path.join(args.repo, doc)
        text = open(path, encoding='utf-8').read()
        for what in tables:
            made = subprocess.run([args.viewer, '--list', what], check=True, capture_output=True, text=True).stdout
            pattern = block_pattern(what)
            found = pattern.search(text)
            if not found:
                print(f'{doc}: no block "<!-- generated: accelviz --list {what} -->" ... "{END}"')
                problems += 1
                continue
            if found.group(2) == made:
                continue
            if args.write:
                text = text[:found.start(2)] + made + text[found.end(2):]
                print(f'{doc}: rewrote the {what} table')
                continue
            problems += 1
            print(f'{doc}: the {what} table differs from `accelviz --list {what}` (the rows in the tools); '
                  f'--write rewrites it:')
            sys.stdout.writelines(difflib.unified_diff(found.group(2).splitlines(True), made.splitlines(True),
                                                       f'{doc}', f'accelviz --list {what}'))
        if args.write:
            with open(path, 'w', encoding='utf-8') as f:
                f.write(text)
    if problems == 0:
        print('the documents\' keys and script tables match the rows')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
