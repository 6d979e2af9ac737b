#!/usr/bin/env python3
"""The folder crossings of one run of the hgrid tool, measured: which functions
of another folder of src/ each folder calls, from a callgrind profile of a
build with -g -fno-inline (every call is a call, nothing inlined away).

  cmake -S . -B /tmp/walk/build -DCMAKE_BUILD_TYPE=Debug \
        -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g -fno-inline" -DHGRID_MPI=OFF
  cmake --build /tmp/walk/build --target hgrid -j2
  valgrind --tool=callgrind --callgrind-out-file=cg.out \
        /tmp/walk/build/hgrid run SCENE.toml --results R --packings P
  python3 bench/folder_walk.py cg.out .            # entry points defined in .cpp files
  python3 bench/folder_walk.py cg.out . --headers  # also header-defined ones (types, templates)

A row "A -> B  n entry functions" lists the distinct functions of folder B
that code of folder A called, and how many calls it made; the walk
crosses A -> B once when both are 1."""
import re, sys, collections, subprocess
out, root = sys.argv[1], sys.argv[2].rstrip('/') + '/src/'
headers = '--headers' in sys.argv[3:]
import os
root = os.path.abspath(root) + '/'
files, fns = {}, {}
fn_file = {}
def name(table, tok):
    m = re.match(r'\((\d+)\)(?: (.*))?', tok)
    if not m: return tok
    i, n = m.group(1), m.group(2)
    if n is not None: table[i] = n
    return table.get(i, '?')
cur_fl = cur_fn = None; callee_fl = None; callee = None
edges = collections.Counter()
for line in open(out, errors='replace'):
    line = line.rstrip('\n')
    if line.startswith('fl='): cur_fl = name(files, line[3:]); continue
    if line.startswith(('fi=', 'fe=')): name(files, line[3:]); continue
    if line.startswith('fn='):
        cur_fn = name(fns, line[3:]); fn_file.setdefault(cur_fn, cur_fl); continue
    if line.startswith(('cfi=', 'cfl=')): callee_fl = name(files, line[4:]); continue
    if line.startswith('cfn='):
        callee = name(fns, line[4:])
        if callee_fl: fn_file.setdefault(callee, callee_fl)
        callee_fl = None; continue
    if line.startswith('calls='):
        edges[(cur_fn, callee)] += int(line[6:].split()[0]); continue
def rel(f):
    """src/-relative path of a source file, also when named through the build's include/hgridlab/ links."""
    f = f or ''
    if f.startswith(root): return f[len(root):]
    if '/include/hgridlab/' in f: return f.split('/include/hgridlab/', 1)[1]
    return None
def folder(fn):
    if 'static_initialization' in fn or fn.startswith('_GLOBAL__'): return None
    r = rel(fn_file.get(fn))
    if not r or '/' not in r or (not headers and not r.endswith('.cpp')): return None
    return r.split('/')[0]
def demangle(names):
    p = subprocess.run(['c++filt'], input='\n'.join(names), capture_output=True, text=True)
    return dict(zip(names, p.stdout.split('\n')))
cross = collections.defaultdict(set)  # (A,B) -> callee entry functions
moves = collections.Counter()          # (A,B) -> calls made
for (a, b), n in edges.items():
    fa, fb = folder(a), folder(b)
    if fa and fb and fa != fb:
        cross[(fa, fb)].add(b)
        moves[(fa, fb)] += n
dm = demangle(sorted({b for s in cross.values() for b in s}))
visited = sorted({rel(fn_file[f]) for f in fn_file if folder(f)})
print(f"files of src/ entered: {len(visited)}; folders: {sorted({v.split('/')[0] for v in visited})}")
total = 0
for (a, b) in sorted(cross):
    s = cross[(a, b)]; total += len(s)
    short = sorted({re.sub(r'\(.*', '', dm.get(x, x)).replace('hgrid::', '') for x in s})
    print(f"{a:>12} -> {b:<12} {moves[(a, b)]:5d} calls {len(s):3d} entry functions: {', '.join(short[:8])}{' ...' if len(short) > 8 else ''}")
print(f"folder pairs crossed: {len(cross)}; entry functions across folders: {total}; calls across folders: {sum(moves.values())}")
