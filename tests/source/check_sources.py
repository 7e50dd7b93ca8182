#!/usr/bin/env python3
"""The source tree keeps the shape the project set itself (issue #29):

  * no source file in core/ or app/ is over 700 lines (one lecture algorithm per file);
  * nothing in app/ compares a structure's name to a literal: what a front end needs of a
    structure comes from its registry entry (core/registry.h);
  * no function in core/ or app/ is over 100 lines, from its signature to its closing brace
    (issue #50: split where its steps are);
  * App is thin (issue #50): at most 20 data members and 800 lines over app/viewer/app.h and
    its app*.cpp files;
  * no test names BVH builders by hand (issue #50): a braced list of two or more builder
    names in tests/ is one the builders' table (bvh_builder_table()) should give; the docs'
    builder lists are checked against the table by tests/docs/check_builder_lists.py;
  * the viewer's tools own their keys and script verbs (issues #42 and #50,
    app/viewer/commands.h): every App file (app/viewer/app.h, app*.cpp) dispatches through
    the rows and the verbs' table and holds no switch over keys, no key a tool binds (a
    GLFW_KEY_ named in app/viewer/tools/), and no verb a tool registers (the
    `add<Args>("verb", ...)` of the *_verbs.h headers; App's own, global_verbs.h, may be named).

    python3 tests/source/check_sources.py [REPO]

Prints one line per offence, 'FILE:LINE: why', and exits 1 when there is any.
"""
import os
import re
import sys

MAX_LINES = 700
MAX_FUNCTION_LINES = 100
MAX_APP_MEMBERS = 20
MAX_APP_LINES = 800
SOURCE = re.compile(r'\.(cpp|h|hpp|cc)$')


def structure_names(repo):
    """The registered names, read from core/registry.cpp's entries."""
    text = open(os.path.join(repo, 'core', 'registry.cpp'), encoding='utf-8').read()
    return re.findall(r'^\s*\{"([a-z_]+)",', text, re.M)


def app_files(repo):
    """App's files: app/viewer/app.h and every app/viewer/app*.cpp."""
    viewer = os.path.join(repo, 'app', 'viewer')
    if not os.path.isdir(viewer):
        return []
    return ['app/viewer/app.h'] + sorted(f'app/viewer/{name}' for name in os.listdir(viewer)
                                         if name.startswith('app') and name.endswith('.cpp'))
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
    for rel in app_files(repo):
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


def without_comments_and_strings(text):
    """`text` with comments removed and string and character literals emptied, newlines kept
    (so braces in them do not count and line numbers stay)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith('//', i):
            j = text.find('\n', i)
            i = n if j < 0 else j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append('\n' * text.count('\n', i, j))
            i = j
        elif text.startswith('R"', i) and re.match(r'R"([^(]*)\(', text[i:]):
            end = ')' + re.match(r'R"([^(]*)\(', text[i:]).group(1) + '"'
            j = text.find(end, i)
            j = n if j < 0 else j + len(end)
            out.append('""' + '\n' * text.count('\n', i, j))
            i = j
        elif text[i] in '"\'' and not (text[i] == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 is a number
            quote, j = text[i], i + 1
            while j < n and text[j] != quote:
                j += 2 if text[j] == '\\' else 1
            out.append(quote * 2)
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return ''.join(out)


# A function's body opens after its parameter list, perhaps with qualifiers or a trailing
# return type between: `) const {`, `) -> std::string {`; if / for / while / switch / catch
# open statements, not functions.
FUNCTION_HEAD = re.compile(r'\)\s*(?:const|override|noexcept|final|mutable|->\s*[\w:<>,\s*&]+|\s)*$')
STATEMENT = re.compile(r'\b(?:if|for|while|switch|catch)\s*\($')


def long_functions(path, limit):
    """(first line, lines, name) of each function (or lambda outside any function) whose body
    spans more than `limit` lines, counted from its signature's first line."""
    text = without_comments_and_strings(open(path, encoding='utf-8').read())
    found, stack, line, depth_in_function = [], [], 1, 0
    for i, c in enumerate(text):
        if c == '\n':
            line += 1
        elif c == '{':
            before = text[max(0, i - 400):i]
            head = before[max(before.rfind(';'), before.rfind('{'), before.rfind('}')) + 1:]
            call = head.split('(')[0] + '(' if '(' in head else ''
            is_function = depth_in_function == 0 and FUNCTION_HEAD.search(head) and not STATEMENT.search(call)
            if is_function:
                names = re.findall(r'([~\w:]+)\s*\(', head)
                stack.append((True, line - head.lstrip('\n').count('\n'), names[0] if names else '?'))
                depth_in_function += 1
            else:
                stack.append((False, line, ''))
        elif c == '}' and stack:
            is_function, first, name = stack.pop()
            if is_function:
                depth_in_function -= 1
                if line - first + 1 > limit:
                    found.append((first, line - first + 1, name))
    return found


def builder_names(repo):
    """The BVH builders' names, read from the table's rows in core/structures/bvh_builders.cpp."""
    text = open(os.path.join(repo, 'core', 'structures', 'bvh_builders.cpp'), encoding='utf-8').read()
    return re.findall(r'\{BvhBuilderKind::\w+,\s*"([a-z_]+)"', text)


def builder_list_problems(repo):
    """Braced lists of builder names in the tests (`{"sah", "binned_sah"}`). "median" and "sah"
    are also the kd-tree's split choices, so a list counts when it names another builder too."""
    names = builder_names(repo)
    if len(names) < 5:
        return [f'core/structures/bvh_builders.cpp:1: found only {names} as BVH builders: the check reads nothing']
    shared = {'median', 'sah'}
    alternatives = '|'.join(map(re.escape, names))
    named = re.compile(rf'"({alternatives})"')
    problems = []
    for folder, _, files in os.walk(os.path.join(repo, 'tests')):
        for name in sorted(files):
            if not SOURCE.search(name):
                continue
            path = os.path.join(folder, name)
            text = open(path, encoding='utf-8').read()
            for braces in re.finditer(r'\{[^{}]*\}', text):
                found = set(named.findall(braces.group(0)))
                if len(found) >= 2 and found - shared:
                    line = text.count('\n', 0, braces.start()) + 1
                    problems.append(f'{os.path.relpath(path, repo)}:{line}: names the builders {sorted(found)} by hand '
                                    '(iterate bvh_builder_table())')
    return problems


def app_problems(repo):
    """App's data members and lines."""
    files = app_files(repo)
    if not files:
        return []
    problems = []
    lines = sum(len(open(os.path.join(repo, rel), encoding='utf-8').read().rstrip('\n').split('\n')) for rel in files)
    if lines > MAX_APP_LINES:
        problems.append(f'app/viewer/app.h:1: App is {lines} lines over {", ".join(files)}, over the '
                        f'{MAX_APP_LINES}-line ceiling (move a tool\'s work into its tool)')
    header = without_comments_and_strings(open(os.path.join(repo, 'app/viewer/app.h'), encoding='utf-8').read())
    body = header[header.find('class App'):]
    # Data members end in an underscore: `Type name_;`, `Type name_ = ...;`, `Type name_{...};`,
    # and a member of an unnamed struct type, `} name_;`.
    members = re.findall(r'^\s*(?:[\w:<>,*&\s()]+?\s|\}\s*)(\w+_)\s*(?:=[^;]*|\{[^;]*\})?;', body, re.M)
    if len(members) > MAX_APP_MEMBERS:
        problems.append(f'app/viewer/app.h:1: App has {len(members)} data members, over the {MAX_APP_MEMBERS} '
                        f'allowed ({", ".join(members)})')
    if not members:
        problems.append('app/viewer/app.h:1: found no data member of App: the check reads nothing')
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
                for first, length, function in long_functions(path, MAX_FUNCTION_LINES):
                    problems.append(f'{rel}:{first}: {function} is {length} lines, over the '
                                    f'{MAX_FUNCTION_LINES}-line ceiling (split it where its steps are)')
                if top == 'app':
                    for number, line in enumerate(lines, 1):
                        if compare.search(line.split('//')[0]):
                            problems.append(f'{rel}:{number}: compares a structure name to a literal '
                                            '(take it from the registry entry)')
    problems += app_problems(repo)
    problems += builder_list_problems(repo)
    problems += dispatch_problems(repo)
    for p in problems:
        print(p)
    print(f'{len(names)} structures, {len(problems)} problems', file=sys.stderr)
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
