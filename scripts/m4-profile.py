#!/usr/bin/env python3
"""Reads QEMU `-d in_asm,exec,nochain` output on stdin; see scripts/m4-profile."""
import sys, re, subprocess, bisect, collections
binary = sys.argv[1]
# symbols
syms = []
for line in subprocess.run(['arm-none-eabi-nm', '-C', '--size-sort', '-S', binary], capture_output=True, text=True).stdout.splitlines():
    parts = line.split(None, 3)
    if len(parts) == 4 and parts[2].lower() in 'tw':
        syms.append((int(parts[0], 16) & ~1, int(parts[1], 16), parts[3]))
syms.sort()
starts = [s[0] for s in syms]
def name(addr):
    i = bisect.bisect_right(starts, addr) - 1
    if i >= 0 and addr < syms[i][0] + syms[i][1]:
        return syms[i][2]
    return '?'
tb_size = {}
tb_last = {}
counts = collections.Counter()
cur = None
n_in = 0
last = None
in_block = False
# The helpers of compiler-builtins (soft float, 64-bit multiply, division, clz, memclr)
# are charged to their call sites as well: each call's instructions (the helper and the
# helpers it calls, until code outside them runs again) go to the instruction before
# the call (the `bl` ending the caller's block).
def helper(fn):
    return fn.startswith('__') or 'compiler_builtins' in fn
is_helper = {}
in_helper = False
site = None
prev = None
site_cost = collections.Counter()
site_calls = collections.Counter()
site_helpers = collections.defaultdict(collections.Counter)
for line in sys.stdin:
    if line.startswith('IN:'):
        in_block = True; cur = None; n_in = 0; continue
    if in_block:
        m = re.match(r'0x([0-9a-f]+):', line)
        if m:
            last = int(m.group(1), 16)
            if cur is None: cur = last
            n_in += 1
            continue
        else:
            if cur is not None: tb_size[cur] = n_in; tb_last[cur] = last
            in_block = False
    m = re.search(r'Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/', line)
    if m:
        pc = int(m.group(1), 16)
        counts[pc] += 1
        h = is_helper.get(pc)
        if h is None:
            h = is_helper[pc] = helper(name(pc))
        if h:
            if not in_helper and prev is not None:
                in_helper = True
                site = tb_last.get(prev, prev)
                site_calls[site] += 1
                site_helpers[site][name(pc)] += 1
            if in_helper:
                site_cost[site] += tb_size.get(pc, 1)
        else:
            in_helper = False
            prev = pc
by_fn = collections.Counter()
total = 0
for pc, c in counts.items():
    w = c * tb_size.get(pc, 1)
    by_fn[name(pc)] += w
    total += w
print('total', total)
def short(fn):
    # typenum's sub-pixel parameter spelled out buries the method name.
    return re.sub(r'typenum::uint::UInt<[^ ]*(, typenum::bit::B[01]>)+', 'U', fn)
# Calls: executions of the block at a function's first address (a loop back to
# the entry would count too; none of the hot functions has one).
entry = {}
for start, _, fn in syms:
    entry.setdefault(fn, start)
print(f'{"instructions":>12} {"share":>6} {"calls":>9} function')
for fn, w in by_fn.most_common(40):
    calls = counts.get(entry.get(fn, -1), 0)
    print(f'{w:12d} {100*w/total:5.1f}% {calls:9d} {short(fn)[:150]}')
# top PCs with inlined frames
import os
top = sorted(((c * tb_size.get(pc, 1), pc) for pc, c in counts.items()), reverse=True)
agg = collections.Counter()
pcs = [pc for _, pc in top[:400]]
out = subprocess.run(['addr2line', '-f', '-i', '-C', '-e', binary] + [hex(p) for p in pcs], capture_output=True, text=True).stdout
# addr2line with -i prints multiple frames per address; rerun per address for clarity
for w, pc in top[:400]:
    o = subprocess.run(['addr2line', '-i', '-e', binary, hex(pc)], capture_output=True, text=True).stdout.split('\n')
    loc = [l for l in o if l.strip()]
    key = ' <- '.join(os.path.basename(l.split(' ')[0]) for l in loc[:3])
    agg[key] += w
print('--- by source (top 400 blocks)')
for k, w in agg.most_common(45):
    print(f'{w:12d} {100*w/total:5.1f}% {k[:160]}')
# The helpers by call site: the caller's inlined frames (innermost first).
helper_total = sum(site_cost.values())
print(f'--- compiler-builtins helpers by call site: {helper_total} instructions '
      f'({100*helper_total/total:.1f}%), {sum(site_calls.values())} calls')
by_fn = collections.Counter()
for fn, w in list(by_fn.items()):
    pass
for pc0, c in counts.items():
    if is_helper.get(pc0):
        by_fn[name(pc0)] += c * tb_size.get(pc0, 1)
print(f'{"instructions":>12} {"calls":>8} helper')
for fn, w in by_fn.most_common(20):
    print(f'{w:12d} {counts.get(entry.get(fn, -1), 0):8d} {fn[:100]}')
sites = [pc0 for pc0, _ in site_cost.most_common(200)]
where = {}
if sites:
    out = subprocess.run(['addr2line', '-a', '-f', '-i', '-C', '-e', binary] + [hex(p) for p in sites],
                         capture_output=True, text=True).stdout.splitlines()
    cur_pc = None
    for l in out:
        if re.match(r'^0x[0-9a-f]+$', l):
            cur_pc = int(l, 16); where[cur_pc] = []
        elif cur_pc is not None:
            where[cur_pc].append(l)
def frames(pc0):
    lines = where.get(pc0, [])
    fr = []
    for fn, loc in zip(lines[0::2], lines[1::2]):
        fn = short(re.sub(r'<.*>', '', fn)).split('::')[-2:]
        fr.append('::'.join(fn) + ' ' + os.path.basename(loc.split(' ')[0]))
    return fr
agg = collections.Counter()
agg_calls = collections.Counter()
agg_helpers = collections.defaultdict(collections.Counter)
for pc0 in sites:
    key = ' <- '.join(frames(pc0)[:3])
    agg[key] += site_cost[pc0]
    agg_calls[key] += site_calls[pc0]
    agg_helpers[key].update(site_helpers[pc0])
print(f'{"instructions":>12} {"calls":>8} call site (inlined frames, innermost first): helpers called')
for k, w in agg.most_common(60):
    hs = ', '.join(f'{re.sub(r".*::", "", h)} {c}' for h, c in agg_helpers[k].most_common(4))
    print(f'{w:12d} {agg_calls[k]:8d} {k[:170]}: {hs}')
