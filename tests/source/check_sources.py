#!/usr/bin/env python3
"""The source tree keeps the shape the project set itself (issue #29):

  * no source file in core/ or app/ is over 700 lines (one lecture algorithm per file);
  * nothing in app/ compares a structure's name to a literal: what a front end needs of a
    structure comes from its registry entry (core/registry.h);
  * the viewer's tools own their keys and script verbs (issues #42 and #50,
    app/viewer/commands.h): app/viewer/app.cpp and app_script.cpp dispatch through the rows
    and the verbs' table and hold no switch over keys, no key a tool binds (a GLFW_KEY_ named
    in app/viewer/tools/), and no verb a tool registers (the `add<Args>("verb", ...)` of the
    *_verbs.h headers; App's own, global_verbs.h, may be named).

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


# The files that dispatch keys and script commands: only App's global ones may be named there.
DISPATCHERS = ('app/viewer/app.cpp', 'app/viewer/app_script.cpp')
KEY = re.compile(r'\bGLFW_KEY_\w+')
# A registration: verbs.template add<HeatmapScale>(\n "heatmap-scale", ...
VERB_REGISTRATION = re.compile(r'\badd<[\w:]+>\(\s*"([a-z0-9][a-z0-9-]*)"')
GLOBAL_VERBS = 'global_verbs.h'


def code_of(line):
    """A line without its // comment (a comment may name a key or a verb)."""
    return line.split('//')[0]


def tool_rows(repo):
    """The keys bound in app/viewer/tools/, and the verbs the tools register."""
    keys, verbs = set(), set()
    viewer = os.path.join(repo, 'app', 'viewer')
    for folder, _, files in os.walk(viewer):
        for name in files:
            if not SOURCE.search(name):
                continue
            text = open(os.path.join(folder, name), encoding='utf-8').read()
            code = '\n'.join(code_of(line) for line in text.split('\n'))
            if os.path.basename(folder) == 'tools':
                keys.update(KEY.findall(code))
            if name.endswith('_verbs.h') and name != GLOBAL_VERBS:
                verbs.update(VERB_REGISTRATION.findall(code))
    return keys, verbs


def dispatch_problems(repo):
    """Per-tool keys and verbs in App's dispatchers."""
    keys, verbs = tool_rows(repo)
    if not keys or not verbs:
        return [f'{repo}/app/viewer: found no tool keys ({len(keys)}) or verbs ({len(verbs)}): the check reads nothing']
    # A verb as a row ({"tree", ...}) or compared (verb == "tree"); a word like "nodes" as a
    # label is no verb.
    alternatives = '|'.join(map(re.escape, sorted(verbs)))
    verb_use = re.compile(rf'(?:\{{\s*|[=!]=\s*)"({alternatives})"|"({alternatives})"\s*[=!]=')
    problems = []
    for rel in DISPATCHERS:
        path = os.path.join(repo, rel)
        if not os.path.exists(path):
            continue
        for number, line in enumerate(open(path, encoding='utf-8').read().split('\n'), 1):
            code = code_of(line)
            if re.search(r'\bcase\s+GLFW_KEY_', code):
                problems.append(f'{rel}:{number}: a switch over keys (dispatch through the rows: commands.h)')
            for key in sorted(set(KEY.findall(code)) & keys):
                problems.append(f'{rel}:{number}: {key} is a tool\'s key (its rows belong in the tool)')
            for verb in (a or b for a, b in verb_use.findall(code)):
                problems.append(f'{rel}:{number}: "{verb}" is a tool\'s script verb (its registration belongs in '
                                'the tool\'s *_verbs.h)')
    return problems


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
    problems += dispatch_problems(repo)
    for p in problems:
        print(p)
    print(f'{len(names)} structures, {len(problems)} problems', file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
