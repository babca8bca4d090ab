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
counts = collections.Counter()
cur = None
n_in = 0
in_block = False
for line in sys.stdin:
    if line.startswith('IN:'):
        in_block = True; cur = None; n_in = 0; continue
    if in_block:
        m = re.match(r'0x([0-9a-f]+):', line)
        if m:
            if cur is None: cur = int(m.group(1), 16)
            n_in += 1
            continue
        else:
            if cur is not None: tb_size[cur] = n_in
            in_block = False
    m = re.search(r'Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/', line)
    if m:
        pc = int(m.group(1), 16)
        counts[pc] += 1
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
