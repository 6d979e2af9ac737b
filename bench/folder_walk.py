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
  python3 bench/folder_walk.py cg.out . --stacks   # does any call stack cross a boundary twice?

A row "A -> B  n entry functions" lists the distinct functions of folder B
that code of folder A called, and how many calls it made: how wide the
boundary is (one door when n is 1).

--stacks reads "a walk crosses each folder boundary at most once each way"
per call stack: no chain of calls goes from folder A into folder B, comes
back to A (returning through a callback, say) and enters B again. It looks
for such a chain on the profile's call graph with header-defined functions
(callbacks, templates) labelled by their folder and every other function
(the standard library's) passed through; the graph's paths include every
stack the run had, so "none" is a proof for this run. Each chain found is
printed, as function names, for a reader to judge."""
import re, sys, collections, subprocess
out, root = sys.argv[1], sys.argv[2].rstrip('/') + '/src/'
stacks = '--stacks' in sys.argv[3:]
headers = '--headers' in sys.argv[3:] or stacks
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
# A function's file is where most of its own instructions lie: a template's
# record can open on a line of the file that instantiated it.
own = collections.defaultdict(collections.Counter)  # function -> file -> instructions
here = None          # the file of the cost lines that follow (fl=, fi=, fe=)
after_call = False   # the cost line after calls= is the call's, not the function's
for line in open(out, errors='replace'):
    line = line.rstrip('\n')
    if line.startswith('fl='): cur_fl = here = name(files, line[3:]); continue
    if line.startswith(('fi=', 'fe=')): here = name(files, line[3:]); continue
    if line.startswith('fn='):
        cur_fn = name(fns, line[3:]); here = cur_fl; fn_file.setdefault(cur_fn, cur_fl); continue
    if line.startswith(('cfi=', 'cfl=')): callee_fl = name(files, line[4:]); continue
    if line.startswith('cfn='):
        callee = name(fns, line[4:])
        if callee_fl: fn_file.setdefault(callee, callee_fl)
        callee_fl = None; continue
    if line.startswith('calls='):
        edges[(cur_fn, callee)] += int(line[6:].split()[0]); after_call = True; continue
    if line[:1].isdigit() or line[:1] in '+-*':
        parts = line.split()
        if not after_call and cur_fn and len(parts) > 1: own[cur_fn][here] += int(parts[1])
        after_call = False
for f, c in own.items(): fn_file[f] = c.most_common(1)[0][0]
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
    names = sorted({re.sub(r'\(.*', '', dm.get(x, x)).replace('hgrid::', '') for x in s})
    print(f"{a:>12} -> {b:<12} {moves[(a, b)]:5d} calls {len(s):3d} entry functions: {', '.join(names[:8])}{' ...' if len(names) > 8 else ''}")
print(f"folder pairs crossed: {len(cross)}; entry functions across folders: {total}; calls across folders: {sum(moves.values())}")

if stacks:
    succ = collections.defaultdict(set)
    for (a, b) in edges: succ[a].add(b)
    allf = sorted(set(succ) | {b for s in succ.values() for b in s})
    dn = demangle(allf)
    label = {f: folder(f) for f in allf}
    def short(n):
        n = n.replace('hgrid::', '').replace('std::', '')
        while True:  # template arguments and parameter lists elided
            m = re.sub(r'<[^<>]*>', '<>', n); m = re.sub(r'\([^()]*\)', '()', m)
            if m == n: break
            n = m
        return n[:110]
    # The stages in their include order (tests/check_includes.sh), the tool
    # last. A call from a stage into a later one can only reach code the later
    # stage handed down (a closure, an executor type): a callback. So is a
    # call into a closure's body whichever way it goes (an executor of a
    # later stage running the runner's work).
    order = re.search(r'^stages=\((.*)\)', open(root + '../tests/check_includes.sh').read(), re.M).group(1).split()
    rank = {st: i for i, st in enumerate(order + ['cli'])}
    def closure(n):
        """Is n (demangled) a closure's body: a lambda's operator() outside any template argument or parameter list?"""
        for m in re.finditer(r'\}::operator\(\)', n):
            head = n[:m.start()]
            if head.count('<') == head.count('>') and head.count('(') == head.count(')') and '{lambda' in head: return True
        return False
    def callback(a, b): return rank[label[a]] < rank[label[b]] or closure(dn.get(b, ''))
    crossing = [(a, b) for (a, b) in edges if label.get(a) and label.get(b) and label[a] != label[b]]
    cut = {e for e in crossing if callback(*e)}
    doors = collections.defaultdict(set)    # (A,B) -> functions of A calling into B
    entered = collections.defaultdict(set)  # (A,B) -> functions of B called from A
    for (a, b) in crossing: doors[(label[a], label[b])].add(a); entered[(label[a], label[b])].add(b)
    def chain(start, goals, skip):
        """A shortest call path from start to a function in goals (not
        following the edges in skip), or None."""
        prev = {start: None}; q = collections.deque([start])
        while q:
            f = q.popleft()
            if f in goals:
                path = []
                while f is not None: path.append(f); f = prev[f]
                return path[::-1]
            for g in succ.get(f, ()):
                if g not in prev and (f, g) not in skip: prev[g] = f; q.append(g)
        return None
    def twice(skip):
        """Boundaries A -> B that some chain crosses, comes back to A and
        crosses again, each with its chain from the first crossing's callee."""
        found = []
        for (A, B) in sorted(doors):
            for g in sorted(entered[(A, B)]):
                p = chain(g, doors[(A, B)], skip)
                if p: found.append((A, B, p)); break
        for (A, B, p) in found:
            print(f"  {A} -> {B} twice, from the first crossing's callee:")
            for f in p: print(f"    {label.get(f) or '-':>8}  {short(dn.get(f, f))}")
        return len(found)
    def both(skip):
        called = {(label[a], label[b]) for (a, b) in crossing if (a, b) not in skip}
        return sorted((a, b) for (a, b) in called if (b, a) in called and a < b)
    print(f"callbacks ({len(cut)}):")
    for (a, b) in sorted(cut, key=lambda e: (label[e[0]], label[e[1]], short(dn.get(e[1], '')))):
        print(f"  {label[a]:>8} -> {label[b]:<8} {short(dn.get(b, b))}")
    print("named calls (callbacks not followed):")
    n = twice(cut)
    print(f"  folder pairs called both ways: {both(cut)}; boundaries a call stack crosses twice the same way: {n}")
    print("all calls (callbacks followed):")
    n = twice(set())
    print(f"  folder pairs called both ways: {both(set())}; boundaries a call stack crosses twice the same way: {n}")
