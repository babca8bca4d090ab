//! The 2-D report of `bench`: the native checks of every fill variant, their
//! instruction counts and the tables.

use std::process::ExitCode;

use host_tests::image::{count_diff, count_set, packed_pixel};
use host_tests::scenes::{bench_triangles, large_polygons, HEIGHT, WIDTH};
use host_tests::tools::callgrind::{
    cpu_model, finish_report, measure_all, ratio, report_header, thousands, tool_version, Table,
};

use super::{
    check_triangles, execute, job_id, shapes, Set, Shapes, Variant, SCALE_COUNT, SCALE_SIZES,
};

/// `bench` without `--scene3d`: checks, measures and prints the fill tables.
pub fn run(markdown: bool, jobs: usize) -> ExitCode {
    // ---- native checks
    let bench = bench_triangles();
    let check = check_triangles(&bench);
    let mut failures = Vec::new();
    if check.span_xor_diff != 0 {
        failures.push(format!(
            "bench set: span and XOR paths differ in {} pixels (first: triangle {:?}, {} px)",
            check.span_xor_diff,
            check.first_span_xor.unwrap().0,
            check.first_span_xor.unwrap().1
        ));
    }
    let mut frames: Vec<(Set, Variant, Vec<u8>)> = Vec::new();
    let large = large_polygons();
    let mut sets = vec![Set::Bench];
    sets.extend((0..large.len()).map(Set::Large));
    sets.extend(SCALE_SIZES.iter().map(|&s| Set::Scale(s)));
    for &set in &sets {
        let sh = shapes(set);
        let variants: &[Variant] = match sh {
            Shapes::Triangles(_) => &Variant::ALL,
            Shapes::Polygons(_) => &[Variant::Span, Variant::Xor],
        };
        for &v in variants {
            frames.push((set, v, execute(v, &sh)));
        }
    }
    let frame = |set: Set, v: Variant| -> &[u8] {
        &frames
            .iter()
            .find(|(s, w, _)| *s == set && *w == v)
            .expect("frame")
            .2
    };
    let pixels = |set: Set, v: Variant| count_set(frame(set, v), WIDTH, HEIGHT);
    for &set in &sets {
        let d = count_diff(
            frame(set, Variant::Span),
            frame(set, Variant::Xor),
            WIDTH,
            HEIGHT,
        );
        if d != 0 {
            let (a, b) = (frame(set, Variant::Span), frame(set, Variant::Xor));
            let first = (0..HEIGHT)
                .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
                .find(|&(x, y)| packed_pixel(a, WIDTH, x, y) != packed_pixel(b, WIDTH, x, y));
            failures.push(format!(
                "{}: span and XOR frames differ in {d} pixels (first at {first:?})",
                set.key()
            ));
        }
        if !matches!(set, Set::Large(_)) {
            let d = count_diff(
                frame(set, Variant::EgPacked),
                frame(set, Variant::EgNaive),
                WIDTH,
                HEIGHT,
            );
            if d != 0 {
                failures.push(format!(
                    "{}: e-g into PackedFramebuffer and into the naive framebuffer differ in {d} pixels",
                    set.key()
                ));
            }
        }
    }

    // ---- instruction counts
    let valgrind = tool_version("valgrind", "--version");
    let mut ids: Vec<String> = vec![job_id(Set::Bench, Variant::Empty)];
    for (set, v, _) in &frames {
        ids.push(job_id(*set, *v));
    }
    let measured = match &valgrind {
        Some(_) => match measure_all(&ids, jobs) {
            Ok(m) => Some(m),
            Err(e) => {
                eprintln!("bench: {e}");
                return ExitCode::from(2);
            }
        },
        None => None,
    };
    let ir = |set: Set, v: Variant| -> u64 {
        let id = job_id(set, v);
        let i = ids.iter().position(|x| *x == id).expect("job");
        let m = &measured.as_ref().expect("measured")[i];
        m.ir
    };
    if let Some(m) = &measured {
        for (i, id) in ids.iter().enumerate().skip(1) {
            let (set, v) = (frames[i - 1].0, frames[i - 1].1);
            if m[i].pixels != pixels(set, v) {
                failures.push(format!(
                    "{id}: under valgrind {} pixels set, natively {}",
                    m[i].pixels,
                    pixels(set, v)
                ));
            }
        }
    }

    // ---- report
    let rustc = tool_version("rustc", "--version").unwrap_or_else(|| "rustc: unknown".into());
    let machine = format!(
        "{}; {}; {} ({}, {} cores)",
        valgrind.as_deref().unwrap_or("valgrind: not found"),
        rustc,
        cpu_model(),
        std::env::consts::ARCH,
        std::thread::available_parallelism().map_or(1, |n| n.get()),
    );
    let mut out = report_header(
        "cargo run --profile figures -p host_tests --bin bench",
        "-- --markdown",
        &machine,
        markdown,
    );
    let tri_note = format!(
        "{} triangles (300 of 2-10 px, 60 of 20-60 px, 12 of 100-240 px), integer pixel-centre vertices, 400 x 240 1-bpp, S = 4",
        bench.len()
    );
    let mut tables = Vec::new();
    if measured.is_some() {
        let base = ir(Set::Bench, Variant::Span);
        let n = bench.len() as u64;
        let rows = Variant::ALL
            .iter()
            .map(|&v| {
                let i = ir(Set::Bench, v);
                let drawn = if matches!(v, Variant::EgPacked | Variant::EgNaive) {
                    check.eg_pixels
                } else {
                    check.pb_pixels
                } as u64;
                vec![
                    v.label().to_string(),
                    thousands(i),
                    thousands(i / n),
                    format!("{:.1}", i as f64 / drawn as f64),
                    thousands(pixels(Set::Bench, v) as u64),
                    ratio(i, base),
                ]
            })
            .collect();
        tables.push(Table {
            title: format!("Fill the fixed triangle set: {tri_note}"),
            header: vec![
                "variant",
                "instructions (Ir)",
                "Ir / triangle",
                "Ir / pixel drawn",
                "pixels set",
                "ratio vs (a)",
            ],
            rows,
        });

        let rows = large
            .iter()
            .enumerate()
            .map(|(i, (name, pts))| {
                let (a, b) = (
                    ir(Set::Large(i), Variant::Span),
                    ir(Set::Large(i), Variant::Xor),
                );
                vec![
                    name.to_string(),
                    pts.len().to_string(),
                    thousands(pixels(Set::Large(i), Variant::Span) as u64),
                    thousands(a),
                    thousands(b),
                    format!(
                        "{:.1}",
                        a as f64 / pixels(Set::Large(i), Variant::Span).max(1) as f64
                    ),
                    format!(
                        "{:.1}",
                        b as f64 / pixels(Set::Large(i), Variant::Span).max(1) as f64
                    ),
                    ratio(b, a),
                ]
            })
            .collect();
        tables.push(Table {
            title: "(d) Large polygons, one fill each (even-odd, 1/16-px vertices)".into(),
            header: vec![
                "polygon",
                "vertices",
                "pixels",
                "(a) span Ir",
                "(b) XOR Ir",
                "(a) Ir/px",
                "(b) Ir/px",
                "XOR / span",
            ],
            rows,
        });

        let rows = SCALE_SIZES
            .iter()
            .map(|&s| {
                let set = Set::Scale(s);
                let per = |v| ir(set, v) / SCALE_COUNT as u64;
                let c = check_triangles(match &shapes(set) {
                    Shapes::Triangles(t) => t,
                    Shapes::Polygons(_) => unreachable!(),
                });
                vec![
                    format!("{s} px"),
                    format!("{:.0}", c.pb_pixels as f64 / SCALE_COUNT as f64),
                    thousands(per(Variant::Span)),
                    thousands(per(Variant::Xor)),
                    ratio(per(Variant::Xor), per(Variant::Span)),
                    thousands(per(Variant::EgPacked)),
                    thousands(per(Variant::EgNaive)),
                    ratio(per(Variant::EgPacked), per(Variant::Span)),
                ]
            })
            .collect();
        tables.push(Table {
            title: format!(
                "(d) Scaling with triangle size: {SCALE_COUNT} triangles per size (vertices on a circle of that diameter), Ir per triangle"
            ),
            header: vec![
                "size",
                "px / tri",
                "(a) span",
                "(b) XOR",
                "XOR / span",
                "(c1) e-g packed",
                "(c2) e-g naive",
                "(c1) / (a)",
            ],
            rows,
        });
    }
    for t in &tables {
        out += &if markdown { t.markdown() } else { t.text() };
        out.push('\n');
    }

    let mut checks = vec![
        format!(
            "span == XOR, triangle by triangle and frame by frame on every set: {}",
            if check.span_xor_diff == 0 && failures.is_empty() {
                "yes"
            } else {
                "NO"
            }
        ),
        format!(
            "e-g vs pbuffer on the {} bench triangles drawn one at a time: pbuffer {} px, e-g {} px; e-g sets {} px pbuffer does not and misses {} px pbuffer sets; {} of {} triangles differ",
            check.triangles,
            check.pb_pixels,
            check.eg_pixels,
            check.eg_extra,
            check.eg_missing,
            check.eg_tris_differing,
            check.triangles
        ),
        format!(
            "e-g into PackedFramebuffer == e-g into the naive framebuffer: {}",
            if failures.iter().any(|f| f.contains("naive")) {
                "NO"
            } else {
                "yes"
            }
        ),
    ];
    if let Some(m) = &measured {
        checks.push(format!(
            "measurement overhead (empty region): {} Ir",
            m[0].ir
        ));
    } else {
        checks.push("valgrind not found: instruction counts skipped".into());
    }
    finish_report(out, &checks, &failures, markdown, measured.is_some())
}
