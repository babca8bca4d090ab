use host_tests::frame::{EngineSpec, ModeSpec, RenderSpec};
use host_tests::pipeline::render_frame;
use host_tests::reference3d::reference_frame;
use std::collections::BTreeMap;

#[test]
#[ignore]
fn beetle_probe() {
    let mesh =
        host_tests::obj::load_obj(std::path::Path::new("../../shared/models/beetle.obj")).unwrap();
    let (w, h) = (400, 240);
    let cam = host_tests::fit::fit_camera(&mesh, w, h);
    let spec = RenderSpec {
        width: w,
        height: h,
        band: h,
        mode: ModeSpec::Dashed,
        engine: EngineSpec::Scanline,
        ..RenderSpec::default()
    };
    let rf = reference_frame(&mesh, &cam, &spec).unwrap();
    let fr = render_frame(&mesh, &cam, &spec).unwrap();
    let m = host_tests::metrics::compare_lines(&fr, &rf);
    println!(
        "hidden len {} missing {} frac {}",
        m.hidden_len,
        m.hidden_missing,
        m.hidden_missing_fraction()
    );
    // per edge
    let mut per: BTreeMap<u32, (f64, f64, f64, f64, usize)> = BTreeMap::new();
    for s in &rf.samples {
        if s.visible {
            continue;
        }
        let near_vis = rf
            .samples
            .iter()
            .any(|o| o.visible && (o.x - s.x).hypot(o.y - s.y) <= 1.0);
        if near_vis {
            continue;
        }
        let (i0, j0) = (s.x.floor() as isize, s.y.floor() as isize);
        let mut found2 = false;
        let mut found1 = false;
        for j in j0 - 2..=j0 + 2 {
            for i in i0 - 2..=i0 + 2 {
                if i < 0 || j < 0 || i >= w as isize || j >= h as isize {
                    continue;
                }
                let (cx, cy) = (i as f64 + 0.5, j as f64 + 0.5);
                if (cx - s.x).hypot(cy - s.y) > 1.5 {
                    continue;
                }
                let v = fr.lines[j as usize * w + i as usize];
                if v == 2 {
                    found2 = true;
                }
                if v == 1 {
                    found1 = true;
                }
            }
        }
        if !found2 {
            let e = per.entry(s.edge).or_insert((0.0, s.x, s.y, s.depth, 0));
            e.0 += s.weight;
            if found1 {
                e.4 += 1;
            }
        }
    }
    let mut v: Vec<_> = per.into_iter().collect();
    v.sort_by(|a, b| b.1 .0.partial_cmp(&a.1 .0).unwrap());
    for (e, (len, x, y, d, vis)) in v.iter().take(15) {
        let re = &rf.edges[*e as usize];
        println!("edge {e} missing {len:.2}px at ({x:.1},{y:.1}) depth {d:.3} with-visible-lib {vis} kind {:?} faces {:?}", re.kind, re.faces);
    }
}

#[test]
#[ignore]
fn beetle_probe2() {
    let mesh =
        host_tests::obj::load_obj(std::path::Path::new("../../shared/models/beetle.obj")).unwrap();
    let (w, h) = (400, 240);
    let cam = host_tests::fit::fit_camera(&mesh, w, h);
    let spec = RenderSpec {
        width: w,
        height: h,
        band: h,
        mode: ModeSpec::Dashed,
        engine: EngineSpec::Scanline,
        ..RenderSpec::default()
    };
    let rf = reference_frame(&mesh, &cam, &spec).unwrap();
    let fr = render_frame(&mesh, &cam, &spec).unwrap();
    for s in rf
        .samples
        .iter()
        .filter(|s| s.edge == 573 && !s.visible)
        .step_by(4)
        .take(6)
    {
        let own = &rf.edges[573].faces;
        let hiders: Vec<_> = (0..rf.faces.len())
            .filter(|&f| {
                rf.faces[f].drawn
                    && !own.contains(&(f as u32))
                    && rf.face_covers(f, s.x, s.y)
                    && rf.face_depth(f, s.x, s.y).is_some_and(|d| d < s.depth)
            })
            .map(|f| (f, rf.face_depth(f, s.x, s.y).unwrap(), rf.faces[f].facing))
            .collect();
        let (i, j) = (s.x as usize, s.y as usize);
        println!(
            "sample ({:.2},{:.2}) d {:.5} hiders {:?} lib id {} ref id {} lib line {}",
            s.x,
            s.y,
            s.depth,
            hiders,
            fr.ids[j * w + i],
            rf.ids[j * w + i],
            fr.lines[j * w + i]
        );
    }
    for f in [343usize, 1337, 1342, 1338] {
        let rfc = &rf.faces[f];
        println!(
            "face {f} facing {} drawn {} normal {:?} verts {:?}",
            rfc.facing, rfc.drawn, rfc.normal, mesh.faces[f]
        );
    }
}
