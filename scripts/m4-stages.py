#!/usr/bin/env python3
"""Reads QEMU `-d in_asm,exec,nochain` output on stdin; see scripts/m4-stages."""
import bisect
import collections
import re
import subprocess
import sys

binary, frames = sys.argv[1], int(sys.argv[2])

# Every executed instruction is charged to the first stage whose pattern matches
# a function of its inlined call chain, searched from the outermost caller in.
STAGES = [
    ('outside', r'fnv1a64|paint_stack|stack_peak|^Reset$|__cortex_m_rt_main$|core::fmt'
                r'|semihosting|BakedMesh>::new|Mesh>::new|with_planar_faces|memcmp'
                r'|with_vertex_faces|with_piercings'),
    # Hidden lines by the segment (the `*-segments` examples): contours, their grid,
    # crossings, piercings and chains, before the rows are drawn.
    ('segments', r'>::by_segment$|fast::segments::'),
    # Out of line on the M0 (their callers unknown here): `eye_space` is mostly the
    # vertex transform's, `faces_view` the face lists', `EdgeStep::new` both the
    # facets' and the lines' set-up ('edge steps').
    ('transform', r'ScreenMap>::(new|with_vertices|vertex|unscaled|on_screen|eye_space)$'),
    ('edge steps', r'EdgeStep>::new$'),
    ('lines: set-up', r'::activate_line'),
    ('lists', r'>::lists(::<.*>)?$|fast::faces_view$'),
    ('face activation', r'>::activate(_other|_clipped)?$|::push_facets$|facets::facet$'
                        r'|::push_with|::set_slope$'),
    ('facet rows', r'ActiveFacets<\d+>>::fill_row|Facet>::|^pbuffer_fill_'),
    ('lines: pixels', r'line_row|ActiveLine>::'),
    ('rows out', r'emit_row|fill_mask|write_mask|Pattern>::word'),
    ('clears', r'clear_row|Framebuffer<.*>::clear$|memclr|memset'),
]
# Issue 23's goals a frame, and for suzanne the stage budgets of
# ../shared/FAST-FRAME.md ("A design that fits 0.8 M", all faces).
example = binary.rsplit('/', 1)[-1]
GOAL = {'suzanne': 800_000, 'panel': 50_000}.get(example)
BUDGET = {
    'transform': 18_000,
    'lists': 11_000 + 8_000,
    'face activation': 70_000,
    'facet rows': 229_000 + 242_000,
    'lines: set-up': None,
    'lines: pixels': None,
    'rows out': None,
    'clears': 13_000,
}
LINES_BUDGET = 211_000  # FAST-FRAME's "lines" covers both line stages
if example != 'suzanne':
    BUDGET, LINES_BUDGET = {}, None


def helpers():
    """The address ranges of compiler-builtins' helpers (soft float, 64-bit multiply,
    division, clz, memclr...): functions named `__...` or from compiler_builtins."""
    ranges = []
    nm = subprocess.run(['arm-none-eabi-nm', '-C', '-S', binary], capture_output=True,
                        text=True).stdout
    for line in nm.splitlines():
        parts = line.split(None, 3)
        if len(parts) == 4 and parts[2].lower() in 'tw' and (
                parts[3].startswith('__') or 'compiler_builtins' in parts[3]):
            start = int(parts[0], 16) & ~1
            ranges.append((start, start + int(parts[1], 16)))
    return sorted(ranges)


HELPERS = helpers()


def is_helper(pc):
    i = bisect.bisect_right(HELPERS, (pc, float('inf'))) - 1
    return i >= 0 and HELPERS[i][0] <= pc < HELPERS[i][1]


def executed():
    """Instruction address -> times executed, and the instructions of helper calls
    charged to their call site: a helper's instructions (and those of the helpers it
    calls, until code outside them runs again) count at the caller's last instruction
    before the call (the `bl` ending its block), so they fall in the caller's stage."""
    blocks, counts = {}, collections.Counter()
    calls = collections.Counter()
    helper_at = {}
    site, prev = None, None
    start, addrs, in_block = None, [], False
    for line in sys.stdin:
        if line.startswith('IN:'):
            in_block, start, addrs = True, None, []
            continue
        if in_block:
            m = re.match(r'0x([0-9a-f]+):', line)
            if m:
                a = int(m.group(1), 16)
                start = a if start is None else start
                addrs.append(a)
                continue
            if start is not None:
                blocks[start] = addrs
            in_block = False
        m = re.search(r'Trace \d+: 0x[0-9a-f]+ \[[0-9a-f]+/([0-9a-f]+)/', line)
        if m:
            pc = int(m.group(1), 16)
            h = helper_at.get(pc)
            if h is None:
                h = helper_at[pc] = is_helper(pc)
            if not h:
                counts[pc] += 1
                site, prev = None, pc
            elif prev is not None:
                if site is None:
                    site = blocks.get(prev, [prev])[-1]
                calls[(site, pc)] += 1
    per, via_helpers = collections.Counter(), collections.Counter()
    for pc, c in counts.items():
        for a in blocks.get(pc, [pc]):
            per[a] += c
    for (a, pc), c in calls.items():
        n = c * len(blocks.get(pc, [pc]))
        per[a] += n
        via_helpers[a] += n
    return per, via_helpers


def chains(addrs):
    """Address -> its inlined call chain (innermost first), through addr2line."""
    out = subprocess.run(['addr2line', '-f', '-i', '-C', '-a', '-e', binary]
                         + [hex(a) for a in addrs], capture_output=True, text=True).stdout
    result, cur, names, odd = {}, None, [], True
    for line in out.splitlines():
        if re.fullmatch(r'0x[0-9a-f]+', line):
            if cur is not None:
                result[cur] = names
            cur, names, odd = int(line, 16), [], True
        else:
            if odd:
                names.append(line)
            odd = not odd
    if cur is not None:
        result[cur] = names
    return result


def symbols():
    """(start, end, name) of the binary's functions, for code without line
    information (the assembly span kernels)."""
    out = subprocess.run(['arm-none-eabi-nm', '-S', binary], capture_output=True, text=True).stdout
    syms = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in 'tT':
            start = int(parts[0], 16) & ~1
            syms.append((start, start + int(parts[1], 16), parts[3]))
    return syms


SYMS = symbols()


def symbol(a):
    return next((n for s, e, n in SYMS if s <= a < e), '??')


per, via_helpers = executed()
stage_of = {}
totals, helper_totals = collections.Counter(), collections.Counter()
for a, names in chains(sorted(per)).items():
    if all(n == '??' for n in names):
        names = [symbol(a)]
    stage = 'frame loop'
    for name in reversed(names):
        hit = next((s for s, pat in STAGES if re.search(pat, name)), None)
        if hit:
            stage = hit
            break
    totals[stage] += per[a]
    helper_totals[stage] += via_helpers[a]
inside = sum(w for s, w in totals.items() if s != 'outside')
# `helpers`: of the stage's instructions, those in compiler-builtins' helpers it calls
# (soft float on the M3 and M0; 64-bit multiply, division and clz on the M0).
print(f'{"stage":<18} {"a frame":>10} {"share":>6} {"helpers":>9} {"budget":>9} {"x budget":>8}')
order = ['transform', 'lists', 'segments', 'edge steps', 'face activation', 'facet rows', 'lines: set-up',
         'lines: pixels', 'rows out', 'clears', 'frame loop']
for s in order:
    if s == 'segments' and not totals[s]:
        continue  # the per-pixel line test: no such stage
    w = totals[s] / frames
    b = BUDGET.get(s)
    ratio = f'{w / b:8.1f}' if b else f'{"":>8}'
    print(f'{s:<18} {w:10.0f} {100 * totals[s] / inside:5.1f}% {helper_totals[s] / frames:9.0f} '
          f'{b or "":>9} {ratio}')
lines = (totals['lines: set-up'] + totals['lines: pixels']) / frames
if LINES_BUDGET:
    print(f'{"lines, both":<18} {lines:10.0f} {"":>6} {LINES_BUDGET:>9} {lines / LINES_BUDGET:8.1f}')
frame = inside / frames
goal = f'{GOAL:>9} {frame / GOAL:8.1f}' if GOAL else ''
helper_frame = sum(w for s, w in helper_totals.items() if s != 'outside') / frames
print(f'{"frame":<18} {frame:10.0f} {"":>6} {helper_frame:9.0f} {goal}')
print(f'(outside the counted frames, not shown: {totals["outside"]} over the run)')
