#!/usr/bin/env python3
"""The pipeline's layout rules (docs/architecture.md), checked over the source tree.

    check_layout.py REPO_ROOT STAGES_JSON   check the tree (STAGES_JSON: <build>/pipeline/stages.json)
    check_layout.py --self-test             plant each kind of violation in a scratch tree; each must be caught

Rules:
  1. A stage's library code (pipeline/<stage>/src, include, cmd) includes only headers of itself, of the
     stages it reaches through its links (stages.json "deps", transitively) and of formats/: never a later
     stage's, never the test helpers (walkrad/testing/). The links themselves are checked by CMake
     (cmake/WalkradStages.cmake: a later stage, or one a stage is forbidden, stops the configuration),
     so a header reached without a link is what is left to catch here.
  2. Only pipeline/visibility/src/extinction_grid.cpp includes OpenVDB; only pipeline/visibility includes
     Embree; runtime/ includes neither, nor any pipeline header.
  3. No file in pipeline/ is over 500 lines unless a comment in its first 15 lines says why
     ("over 500 lines" and the reason).
  4. The `walkrad` command (pipeline/cli/, a tool, not a stage) includes only the last stage's headers and
     what it reaches, and the accuracy stage's (its sweep): the bake library itself never links accuracy.
Exit 0 when the tree follows them, 1 with one line per violation otherwise.
"""
import json
import os
import re
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]', re.M)
MAX_LINES = 500


def closure(stage, deps):
    seen, todo = set(), [stage]
    while todo:
        for d in deps.get(todo.pop(), []):
            if d not in seen:
                seen.add(d)
                todo.append(d)
    return seen


def sources(folder):
    for root, _, files in os.walk(folder):
        for f in sorted(files):
            if f.endswith(('.h', '.hpp', '.cpp', '.cc', '.in')):
                yield os.path.join(root, f)


def check(repo, stages):
    order, deps = stages['order'], stages['deps']
    problems = []
    pipeline = os.path.join(repo, 'pipeline')
    for stage in order:
        allowed = closure(stage, deps) | {stage, 'formats'}
        for part in ('src', 'include', 'cmd'):
            for path in sources(os.path.join(pipeline, stage, part)):
                rel = os.path.relpath(path, repo)
                text = open(path, encoding='utf-8').read()
                for inc in INCLUDE.findall(text):
                    parts = inc.split('/')
                    if len(parts) >= 3 and parts[0] == 'walkrad':
                        other = parts[1]
                        if other == 'testing':
                            problems.append(f'{rel}: includes {inc}: test helpers are not library code')
                        elif other in order and other not in allowed:
                            later = order.index(other) > order.index(stage)
                            why = 'a later stage' if later else 'a stage it does not link'
                            problems.append(f'{rel}: includes {inc}, a header of {why} ({other})')
                    if inc.startswith('openvdb/') and rel != 'pipeline/visibility/src/extinction_grid.cpp':
                        problems.append(f'{rel}: includes {inc}: only the extinction grid sees OpenVDB')
                    if inc.startswith('embree') and stage != 'visibility':
                        problems.append(f'{rel}: includes {inc}: only the visibility stage sees Embree')
    # The command: the last stage (the bake) and what it reaches, and the accuracy stage (its sweep).
    tool_allowed = closure(order[-1], deps) | {order[-1], 'formats', 'accuracy'} if order else set()
    for path in sources(os.path.join(pipeline, 'cli')):
        rel = os.path.relpath(path, repo)
        for inc in INCLUDE.findall(open(path, encoding='utf-8').read()):
            parts = inc.split('/')
            if len(parts) >= 3 and parts[0] == 'walkrad' and (parts[1] == 'testing' or (parts[1] in order and parts[1] not in tool_allowed)):
                problems.append(f'{rel}: includes {inc}: the command reaches the bake and the sweep only')
    for path in sources(os.path.join(repo, 'runtime')):
        rel = os.path.relpath(path, repo)
        for inc in INCLUDE.findall(open(path, encoding='utf-8').read()):
            parts = inc.split('/')
            if inc.startswith(('openvdb/', 'embree')) or (len(parts) >= 3 and parts[0] == 'walkrad' and parts[1] in order):
                problems.append(f'{rel}: includes {inc}: the runtime links formats\' read side only')
    for path in sources(pipeline):
        lines = open(path, encoding='utf-8').read().split('\n')
        if len(lines) > MAX_LINES and not any('over 500 lines' in l for l in lines[:15]):
            problems.append(f'{os.path.relpath(path, repo)}: {len(lines)} lines, over {MAX_LINES} with no reason at its top')
    return problems


def self_test():
    """Each planted fault must be reported; the clean tree must not be."""
    stages = {'order': ['core', 'scene', 'classic', 'accuracy', 'bake'],
              'deps': {'core': [], 'scene': ['core'], 'classic': ['scene'], 'accuracy': ['scene'], 'bake': ['scene']}}
    files = {
        'pipeline/core/src/a.cpp': '#include "walkrad/core/a.h"\n',
        'pipeline/scene/src/b.cpp': '#include "walkrad/core/a.h"\n#include "walkrad/formats/scene.h"\n',
        'pipeline/classic/include/walkrad/classic/c.h': '#include "walkrad/scene/b.h"\n',
        'pipeline/accuracy/src/d.cpp': '#include "walkrad/scene/b.h"\n',
        'runtime/src/e.cpp': '#include "walkrad/formats/manifest.h"\n',
        'pipeline/cli/main.cpp': '#include "walkrad/bake/f.h"\n#include "walkrad/accuracy/d.h"\n',
    }
    faults = [
        ('pipeline/scene/src/late.cpp', '#include "walkrad/classic/c.h"\n', 'a header of a later stage (classic)'),
        ('pipeline/accuracy/src/tracer.cpp', '#include "walkrad/classic/c.h"\n', 'a stage it does not link (classic)'),
        ('pipeline/scene/src/vdb.cpp', '#include <openvdb/openvdb.h>\n', 'only the extinction grid sees OpenVDB'),
        ('pipeline/core/src/helper.cpp', '#include "walkrad/testing/test_scenes.h"\n', 'test helpers are not library code'),
        ('runtime/src/bad.cpp', '#include "walkrad/scene/b.h"\n', "the runtime links formats' read side only"),
        ('pipeline/core/src/long.cpp', '\n' * 600, 'over 500 with no reason'),
        ('pipeline/cli/solve.cpp', '#include "walkrad/classic/c.h"\n', 'the command reaches the bake and the sweep only'),
    ]
    failures = 0

    def build(root, extra):
        for rel, text in list(files.items()) + extra:
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            open(path, 'w').write(text)

    with tempfile.TemporaryDirectory() as root:
        build(root, [])
        if check(root, stages):
            print('self-test: the clean tree was reported:', check(root, stages))
            failures += 1
    for rel, text, expect in faults:
        with tempfile.TemporaryDirectory() as root:
            build(root, [(rel, text)])
            found = check(root, stages)
            if not any(expect in p for p in found):
                print(f'self-test: {rel} ({expect}) not caught; reported: {found}')
                failures += 1
    print(f'{len(faults) + 1 - failures} passed, {failures} failed')
    return 1 if failures else 0


def main(argv):
    if argv[1:] == ['--self-test']:
        return self_test()
    if len(argv) != 3:
        print(__doc__)
        return 2
    with open(argv[2]) as f:
        stages = json.load(f)
    problems = check(argv[1], stages)
    for p in problems:
        print(p)
    print(f'layout: {len(stages["order"])} stages, {len(problems)} violations')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
