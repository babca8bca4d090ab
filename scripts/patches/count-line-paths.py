#!/usr/bin/env python3
"""The line-pass counting patch of scripts/count-line-paths: atomic counters in lines.rs, printed by host_tests' firmware_examples. Usage: count-line-paths.py TREE"""
import sys
t = sys.argv[1]
def sub(path, old, new, count=1):
    p = f"{t}/{path}"
    s = open(p).read()
    assert s.count(old) >= 1, (path, old)
    s = s.replace(old, new, count)
    open(p, "w").write(s)
sub("src/lib.rs", "pub mod bake;",
    "#[doc(hidden)]\npub static LINE_COUNTS: [core::sync::atomic::AtomicU32; 16] = [const { core::sync::atomic::AtomicU32::new(0) }; 16];\n#[doc(hidden)]\npub fn line_count(i: usize) { LINE_COUNTS[i].fetch_add(1, core::sync::atomic::Ordering::Relaxed); }\npub mod bake;")
open(f"{t}/COUNT_NAMES", "w").write(
 "0 pixels tested\n1 pass first compare (visible by one compare: 0 - 1)\n2 decided by the margin (face found last, apart)\n3 slow: own face\n4 slow: rules entered (hidden_by)\n5 slow: face looked up\n6 slow: not nearer at edge\n7 next column empty (any path)\n8 beside Apart\n9 beside Covers\n10 beside Misses\n11 hidden (final)\n12 steep pixels\n")
L = "src/render/engines/fast/lines.rs"
c = lambda i: f"crate::line_count({i});"
sub(L, "        let Some(&cell) = at.row.get(x as usize) else {\n            return;\n        };",
       "        let Some(&cell) = at.row.get(x as usize) else {\n            return;\n        };\n        if at.test == LineTest::Row { " + c(0) + " if !self.x_major { " + c(12) + " } if cell & 0xFFFF_0000 > c.d.saturating_add(self.bias) { " + c(1) + " } }")
sub(L, """            {
                self.x_major || next_shows_face(at.row, x, c.q, at.s)
            } else {
                !self.owns(cell) && self.hidden_by(cell, x, c, at)
            };""", """            {
                """ + c(2) + """
                self.x_major || next_shows_face(at.row, x, c.q, at.s)
            } else {
                if self.owns(cell) { """ + c(3) + """ }
                !self.owns(cell) && { """ + c(4) + """ self.hidden_by(cell, x, c, at) }
            };""")
sub(L, "        let mask = if hide { hidden } else { visible };", "        if hide { " + c(11) + " }\n        let mask = if hide { hidden } else { visible };")
sub(L, "        if !self.nearer_at_edge(cell, d, q, s, at.faces) {\n            return false;", "        if !self.nearer_at_edge(cell, d, q, s, at.faces) {\n            " + c(6) + "\n            return false;")
sub(L, "    off == 0\n        || row\n            .get((x + off.signum()) as usize)\n            .is_some_and(|&n| n != 0)",
       "    let r = off == 0 || row.get((x + off.signum()) as usize).is_some_and(|&n| n != 0);\n    if !r { " + c(7) + " }\n    r")
sub(L, "            Beside::Apart => {\n", "            Beside::Apart => {\n                " + c(8) + "\n")
sub(L, "            Beside::Covers => true,", "            Beside::Covers => { " + c(9) + " true }")
sub(L, "            Beside::Misses => false,", "            Beside::Misses => { " + c(10) + " false }")
sub(L, "        if id != self.near {\n", "        if id != self.near {\n            " + c(5) + "\n")
F = "host_tests/tests/firmware/firmware_examples.rs"
sub(F, '    println!("frame {name} {n} hash={:016x}", fnv1a64(bytes));',
 '    println!("frame {name} {n} hash={:016x}", fnv1a64(bytes));\n    let c: Vec<u32> = pbuffer::LINE_COUNTS.iter().map(|a| a.swap(0, std::sync::atomic::Ordering::Relaxed)).collect();\n    println!("counts {name} {n} {:?}", c);')
