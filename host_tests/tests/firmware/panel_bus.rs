//! The driver examples (`panel-ssd1306`, `suzanne-sharp`) on the host: the same code
//! (`pbuffer_scenes::panels` and `scenes`, the firmware's crate) drives the
//! `ssd1306` and `sharp-memory-display` crates, and the bytes they write to the bus are
//! checked to be exactly the frame, the frame the host renders into pbuffer's
//! `PackedFramebuffer` for the same view (the `panel` and `suzanne` examples' frames,
//! whose hashes `scripts/firmware` compares with the firmware's):
//!
//! - recorded bus bytes are decoded back into pixels by a model of each panel's
//!   protocol written from its datasheet (SSD1306: I2C control byte 0x00 for commands,
//!   0x40 for data, column/page address commands, horizontal addressing, 8 vertical
//!   pixels a byte LSB on top; Sharp memory LCD: write command M0 = 1 with the VCOM bit
//!   M1, per line its address, 1-based, bits reversed (sent LSB first), 50 data bytes,
//!   leftmost pixel in the MSB, a dummy byte; a dummy byte to end), and compared pixel
//!   by pixel, for the three ways the firmware measures (fill_solid, `Pixels`, copy);
//! - `embedded-hal-mock` buses expect, write by write, the bytes encoded from the
//!   reference frame, and fail on any other byte;
//! - a one-pixel change and a wrong bit order are shown to be caught;
//! - the reference frames are `render --hash` of the same views (the `render`
//!   command run on the same mesh and camera).
//!
//! Prints `frame EXAMPLE N hash=HEX` (FNV-1a 64 of the bus bytes of each frame's
//! flush, as the firmware hashes them), which `scripts/firmware` compares with the
//! firmware's lines.

use pbuffer_scenes::{obj, panels, scenes};

use std::cell::RefCell;
use std::panic::{catch_unwind, AssertUnwindSafe};

use embedded_graphics::pixelcolor::BinaryColor;
use embedded_graphics::prelude::{DrawTarget, Point};
use embedded_graphics::Pixel;
use embedded_hal_mock::eh0::digital::{Mock as PinMock, State, Transaction as PinT};
use embedded_hal_mock::eh0::spi::{Mock as SpiMock, Transaction as SpiT};
use embedded_hal_mock::eh1::i2c::{Mock as I2cMock, Transaction as I2cT};
use host_tests::firmware::Bake;
use panels::{NoPin, Record, Sharp, Tap};
use pbuffer::render::BakedMesh;
use pbuffer::{packed_len, DrawMode, PackedFramebuffer};
use scenes::{fnv1a64, panel, suzanne};
use ssd1306::mode::DisplayConfig;

type PanelFb = PackedFramebuffer<128, 64, { packed_len(128, 64) }>;
type SharpFb = PackedFramebuffer<400, 240, { packed_len(400, 240) }>;
const ADDRESS: u8 = 0x3C;

/// Bakes a mesh as build.rs does and hands it to `f`.
fn with_baked<R>(v: &[[f32; 3]], i: &[u32], o: &[u32], f: impl FnOnce(&BakedMesh<'_>) -> R) -> R {
    f(&Bake::new(v, i, o).baked())
}

/// Runs `f` on a thread with room for the buffers.
fn big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("the test passes");
}

/// A pixel of a decoded frame that differs from the reference: (x, y).
fn differences(
    decoded: &[bool],
    width: usize,
    reference: impl Fn(u32, u32) -> bool,
) -> Vec<(usize, usize)> {
    decoded
        .iter()
        .enumerate()
        .filter(|&(k, &on)| on != reference((k % width) as u32, (k / width) as u32))
        .map(|(k, _)| (k % width, k / width))
        .collect()
}

/// The SSD1306's display RAM after the I2C writes `writes` (each with its control
/// byte), read back as 128 x 64 pixels (not rotated: column x, row y).
fn decode_ssd1306(writes: &[&[u8]]) -> Vec<bool> {
    let mut ram = [[0u8; 128]; 8];
    let (mut cols, mut pages) = ((0usize, 127usize), (0usize, 7usize));
    let (mut col, mut page) = (0, 0);
    for w in writes {
        match w.first() {
            Some(0x00) => match w.get(1) {
                Some(0x21) => {
                    cols = (usize::from(w[2]), usize::from(w[3]));
                    col = cols.0;
                }
                Some(0x22) => {
                    pages = (usize::from(w[2]), usize::from(w[3]));
                    page = pages.0;
                }
                _ => {} // set-up commands: no pixels
            },
            Some(0x40) => {
                for &b in &w[1..] {
                    ram[page][col] = b;
                    col += 1;
                    if col > cols.1 {
                        col = cols.0;
                        page = if page >= pages.1 { pages.0 } else { page + 1 };
                    }
                }
            }
            other => panic!("not an SSD1306 I2C control byte: {other:?}"),
        }
    }
    (0..64 * 128)
        .map(|k| ram[k / 128 / 8][k % 128] >> (k / 128 % 8) & 1 == 1)
        .collect()
}

/// The writes of a record: its bytes split where each write ended.
fn writes<'r>(rec: &'r Record<'_>) -> Vec<&'r [u8]> {
    let mut start = 0;
    rec.ends()
        .iter()
        .map(|&end| {
            let w = &rec.bytes()[start..end as usize];
            start = end as usize;
            w
        })
        .collect()
}

/// The 400 x 240 pixels one Sharp memory LCD update (`bytes`, one chip-select
/// frame) writes; every line must be written once.
fn decode_sharp(bytes: &[u8], msb_first: bool) -> Vec<bool> {
    assert_eq!(
        bytes[0] & 0xBF,
        0x80,
        "a write-line command (M0 = 1, M2 = 0)"
    );
    let body = &bytes[1..bytes.len() - 1];
    assert_eq!(bytes[bytes.len() - 1], 0, "the closing dummy byte");
    assert_eq!(
        body.len(),
        240 * 52,
        "240 lines of address, 50 bytes, dummy"
    );
    let mut pixels = vec![false; 400 * 240];
    let mut seen = [false; 240];
    for line in body.chunks_exact(52) {
        let y = usize::from(line[0].reverse_bits()) - 1;
        assert!(!seen[y], "line {y} written twice");
        seen[y] = true;
        assert_eq!(line[51], 0, "the dummy byte after line {y}");
        for x in 0..400 {
            let bit = if msb_first {
                0x80 >> (x % 8)
            } else {
                1 << (x % 8)
            };
            pixels[y * 400 + x] = line[1 + x / 8] & bit != 0;
        }
    }
    pixels
}

/// The I2C writes of one full-screen SSD1306 update of `fb`, from the datasheet:
/// column range 0..127, page range 0..7, then the page bytes 16 a write.
fn expect_ssd1306(fb: &PanelFb) -> Vec<I2cT> {
    let mut t = vec![
        I2cT::write(ADDRESS, vec![0x00, 0x21, 0, 127]),
        I2cT::write(ADDRESS, vec![0x00, 0x22, 0, 7]),
    ];
    let ram: Vec<u8> = (0..8)
        .flat_map(|p| (0..128).map(move |c| fb.page_byte(p, c)))
        .collect();
    for chunk in ram.chunks(16) {
        t.push(I2cT::write(ADDRESS, [&[0x40], chunk].concat()));
    }
    t
}

/// The SPI writes of one Sharp update of `fb` (VCOM bit `vcom`), from the datasheet;
/// `msb_first: false` encodes the data bytes with the wrong bit order.
fn expect_sharp(fb: &SharpFb, vcom: bool, msb_first: bool) -> Vec<SpiT> {
    let mut t = vec![SpiT::write(vec![0x80 | if vcom { 0x40 } else { 0 }])];
    for (y, row) in fb.as_bytes().chunks_exact(50).enumerate() {
        let mut line = vec![(y as u8 + 1).reverse_bits()];
        line.extend(
            row.iter()
                .map(|&b| if msb_first { b } else { b.reverse_bits() }),
        );
        line.push(0);
        t.push(SpiT::write(line));
    }
    t.push(SpiT::write(vec![0]));
    t
}

/// The panel's reference frames: pbuffer's `PackedFramebuffer`, as the `panel` example.
fn panel_frames(baked: &BakedMesh<'_>) -> Vec<PanelFb> {
    let mut engine = Box::new(scenes::PanelFastEngine::new());
    let mut b = Box::new(scenes::PanelFastBuffers::new());
    (0..panel::FRAMES)
        .map(|n| {
            let mut fb = PanelFb::new();
            scenes::render_fast(
                &mut engine,
                baked,
                &panel::view(n),
                DrawMode::Dashed,
                &mut b.workspace(),
                &mut fb,
            )
            .expect("renders");
            fb
        })
        .collect()
}

/// Suzanne's reference frames, as the `suzanne` example.
fn suzanne_frames(baked: &BakedMesh<'_>) -> Vec<SharpFb> {
    let mut engine = Box::new(scenes::FastEngine::new());
    let mut b = Box::new(scenes::SuzanneFastBuffers::new());
    (0..suzanne::FRAMES)
        .map(|n| {
            let mut fb = SharpFb::new();
            scenes::render_fast(
                &mut engine,
                baked,
                &suzanne::view(n),
                DrawMode::Dashed,
                &mut b.workspace(),
                &mut fb,
            )
            .expect("renders");
            fb
        })
        .collect()
}

fn panel_baked<R>(f: impl FnOnce(&BakedMesh<'_>) -> R) -> R {
    with_baked(&panel::VERTICES, &panel::INDICES, &panel::OFFSETS, f)
}

fn suzanne_baked<R>(f: impl FnOnce(&BakedMesh<'_>) -> R) -> R {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/embedded/models/suzanne.obj"
    );
    let text = std::fs::read_to_string(path).expect("read the examples' suzanne.obj");
    let m = obj::parse(&text, "suzanne.obj").expect("parses");
    with_baked(&m.vertices, &m.indices, &m.offsets, f)
}

/// The firmware's `panel-ssd1306` run, on a recording bus: per frame the three ways
/// (fill_solid, `Pixels`, copy), each flushed and decoded against the reference.
#[test]
fn ssd1306_bus_bytes_are_the_frame() {
    big_stack(|| {
        panel_baked(|baked| {
            let refs = panel_frames(baked);
            let (mut bytes, mut ends) = (vec![0u8; 2048], vec![0u32; 128]);
            let record = RefCell::new(Record::new(&mut bytes, &mut ends));
            let mut display = panels::ssd1306_display(Tap(&record));
            display.init().expect("init");
            let mut engine = Box::new(scenes::PanelFastEngine::new());
            let mut b = Box::new(scenes::PanelFastBuffers::new());
            for (n, reference) in refs.iter().enumerate() {
                let view = panel::view(n as u32);
                let mut flushed = Vec::new();
                for way in 0..3 {
                    display.clear_buffer();
                    let ws = &mut b.workspace();
                    match way {
                        0 => drop(
                            panels::render_fill_solid(&mut engine, baked, &view, ws, &mut display)
                                .expect("renders"),
                        ),
                        1 => drop(
                            panels::render_direct(&mut engine, baked, &view, ws, &mut display)
                                .expect("renders"),
                        ),
                        _ => panels::copy_frame(reference, &mut display).expect("copies"),
                    }
                    record.borrow_mut().clear();
                    display.flush().expect("flushes");
                    let rec = record.borrow();
                    assert_eq!(rec.lost(), 0);
                    let decoded = decode_ssd1306(&writes(&rec));
                    let diff = differences(&decoded, 128, |x, y| reference.pixel(x, y));
                    assert!(
                        diff.is_empty(),
                        "panel frame {n}, way {way}: {} pixels differ, first {:?}",
                        diff.len(),
                        diff[0]
                    );
                    flushed.push(rec.bytes().to_vec());
                }
                assert!(
                    flushed.iter().all(|f| *f == flushed[1]),
                    "the three ways write the same bytes"
                );
                println!("frame panel-ssd1306 {n} hash={:016x}", fnv1a64(&flushed[1]));
            }
        })
    });
}

/// The firmware's `suzanne-sharp` run, on a recording bus: the three ways, decoded.
#[test]
fn sharp_bus_bytes_are_the_frame() {
    big_stack(|| {
        suzanne_baked(|baked| {
            let refs = suzanne_frames(baked);
            let (mut bytes, mut ends) = (vec![0u8; 12_800], vec![0u32; 256]);
            let record = RefCell::new(Record::new(&mut bytes, &mut ends));
            let mut display = Box::new(panels::sharp_display(Tap(&record), NoPin, NoPin));
            display.clear();
            let mut engine = Box::new(scenes::FastEngine::new());
            let mut b = Box::new(scenes::SuzanneFastBuffers::new());
            let mut vcom = Vec::new();
            for (n, reference) in refs.iter().enumerate() {
                let view = suzanne::view(n as u32);
                let mut flushed = Vec::new();
                for way in 0..3 {
                    display.clear_buffer();
                    let ws = &mut b.workspace();
                    let target = &mut Sharp(&mut *display);
                    match way {
                        0 => drop(
                            panels::render_fill_solid(&mut engine, baked, &view, ws, target)
                                .expect("renders"),
                        ),
                        1 => drop(
                            panels::render_direct(&mut engine, baked, &view, ws, target)
                                .expect("renders"),
                        ),
                        _ => panels::copy_frame(reference, target).expect("copies"),
                    }
                    record.borrow_mut().clear();
                    display.flush_buffer();
                    let rec = record.borrow();
                    assert_eq!(rec.lost(), 0);
                    let decoded = decode_sharp(rec.bytes(), true);
                    let diff = differences(&decoded, 400, |x, y| reference.pixel(x, y));
                    assert!(
                        diff.is_empty(),
                        "suzanne frame {n}, way {way}: {} pixels differ, first {:?}",
                        diff.len(),
                        diff[0]
                    );
                    vcom.push(rec.bytes()[0] & 0x40 != 0);
                    flushed.push(rec.bytes().to_vec());
                }
                assert!(
                    flushed.iter().all(|f| f[1..] == flushed[1][1..]),
                    "the three ways write the same lines"
                );
                println!("frame suzanne-sharp {n} hash={:016x}", fnv1a64(&flushed[1]));
            }
            assert!(
                vcom.windows(2).all(|w| w[0] != w[1]),
                "VCOM inverts at every update"
            );
        })
    });
}

/// The driven bytes against `embedded-hal-mock`: the SSD1306's I2C bus expects, write
/// by write, the page bytes encoded from each reference frame (its set-up writes, which
/// carry no pixels, are taken as the driver sends them), the Sharp's SPI bus and pins
/// the datasheet's update of each frame.
#[test]
fn mock_buses_take_exactly_the_frames() {
    big_stack(|| {
        panel_baked(|baked| {
            let refs = panel_frames(baked);
            let mut i2c = I2cMock::new(&init_writes());
            let mut display = panels::ssd1306_display(i2c.clone());
            display.init().expect("init");
            let mut engine = Box::new(scenes::PanelFastEngine::new());
            let mut b = Box::new(scenes::PanelFastBuffers::new());
            for (n, reference) in refs.iter().enumerate() {
                i2c.update_expectations(&expect_ssd1306(reference));
                display.clear_buffer();
                let view = panel::view(n as u32);
                panels::render_direct(&mut engine, baked, &view, &mut b.workspace(), &mut display)
                    .expect("renders");
                display.flush().expect("flushes");
            }
            i2c.done();
        });
        suzanne_baked(|baked| {
            let refs = suzanne_frames(baked);
            let mut spi = SpiMock::new(&[SpiT::write(vec![0x20, 0])]);
            let mut cs = PinMock::new(&[
                PinT::set(State::Low),
                PinT::set(State::High),
                PinT::set(State::Low),
            ]);
            let mut disp = PinMock::new(&[PinT::set(State::Low), PinT::set(State::High)]);
            let mut display =
                Box::new(panels::sharp_display(spi.clone(), cs.clone(), disp.clone()));
            display.clear();
            let mut engine = Box::new(scenes::FastEngine::new());
            let mut b = Box::new(scenes::SuzanneFastBuffers::new());
            for (n, reference) in refs.iter().enumerate() {
                spi.update_expectations(&expect_sharp(reference, n % 2 == 0, true));
                cs.update_expectations(&[PinT::set(State::High), PinT::set(State::Low)]);
                display.clear_buffer();
                let view = suzanne::view(n as u32);
                let target = &mut Sharp(&mut *display);
                panels::render_direct(&mut engine, baked, &view, &mut b.workspace(), target)
                    .expect("renders");
                display.flush_buffer();
            }
            spi.done();
            cs.done();
            disp.done();
        });
    });
}

/// The SSD1306's set-up writes as the driver sends them (they carry no pixels).
fn init_writes() -> Vec<I2cT> {
    let (mut bytes, mut ends) = (vec![0u8; 1024], vec![0u32; 64]);
    let record = RefCell::new(Record::new(&mut bytes, &mut ends));
    let mut display = panels::ssd1306_display(Tap(&record));
    display.init().expect("init");
    let rec = record.borrow();
    writes(&rec)
        .iter()
        .map(|w| I2cT::write(ADDRESS, w.to_vec()))
        .collect()
}

/// Turns pixel (x, y) of `fb` over.
fn flip<D: DrawTarget<Color = BinaryColor>>(fb: &mut D, on: bool, x: i32, y: i32) {
    let c = if on {
        BinaryColor::Off
    } else {
        BinaryColor::On
    };
    let _ = fb.draw_iter([Pixel(Point::new(x, y), c)]);
}

/// The checks can fail: one pixel changed in the reference, or the Sharp data bytes
/// in the wrong bit order, is seen by the decoders and by the mock buses.
#[test]
fn a_changed_pixel_or_a_wrong_bit_order_is_caught() {
    big_stack(|| {
        panel_baked(|baked| {
            let refs = panel_frames(baked);
            let mut changed = refs[0].clone();
            flip(&mut changed, refs[0].pixel(37, 21), 37, 21);
            let (mut bytes, mut ends) = (vec![0u8; 2048], vec![0u32; 128]);
            let record = RefCell::new(Record::new(&mut bytes, &mut ends));
            let mut display = panels::ssd1306_display(Tap(&record));
            display.init().expect("init");
            panels::copy_frame(&refs[0], &mut display).expect("copies");
            record.borrow_mut().clear();
            display.flush().expect("flushes");
            let decoded = decode_ssd1306(&writes(&record.borrow()));
            assert_eq!(
                differences(&decoded, 128, |x, y| changed.pixel(x, y)),
                vec![(37, 21)]
            );
            // The mock expecting the changed frame rejects the real one, and takes it
            // when it expects the real one.
            assert!(ssd1306_mock_takes(&refs[0], &refs[0]));
            assert!(
                !ssd1306_mock_takes(&changed, &refs[0]),
                "the I2C mock takes a frame one pixel off"
            );
        });
        suzanne_baked(|baked| {
            let refs = suzanne_frames(baked);
            let (mut bytes, mut ends) = (vec![0u8; 12_800], vec![0u32; 256]);
            let record = RefCell::new(Record::new(&mut bytes, &mut ends));
            let mut display = Box::new(panels::sharp_display(Tap(&record), NoPin, NoPin));
            panels::copy_frame(&refs[0], &mut Sharp(&mut *display)).expect("copies");
            record.borrow_mut().clear();
            display.flush_buffer();
            let rec = record.borrow();
            let wrong_order = decode_sharp(rec.bytes(), false);
            assert!(!differences(&wrong_order, 400, |x, y| refs[0].pixel(x, y)).is_empty());
            let mut changed = refs[0].clone();
            flip(&mut changed, refs[0].pixel(201, 117), 201, 117);
            let decoded = decode_sharp(rec.bytes(), true);
            assert_eq!(
                differences(&decoded, 400, |x, y| changed.pixel(x, y)),
                vec![(201, 117)]
            );
            assert!(sharp_mock_takes(&refs[0], true, &refs[0]));
            assert!(
                !sharp_mock_takes(&changed, true, &refs[0]),
                "the SPI mock takes a frame one pixel off"
            );
            assert!(
                !sharp_mock_takes(&refs[0], false, &refs[0]),
                "the SPI mock takes LSB-first data bytes"
            );
        });
    });
}

/// Whether an I2C mock that expects the update of `expected` takes the update the
/// driver writes for `drawn` (copied into its buffer).
fn ssd1306_mock_takes(expected: &PanelFb, drawn: &PanelFb) -> bool {
    catch_unwind(AssertUnwindSafe(|| {
        let mut i2c = I2cMock::new(&init_writes());
        let mut d = panels::ssd1306_display(i2c.clone());
        d.init().expect("init");
        i2c.update_expectations(&expect_ssd1306(expected));
        panels::copy_frame(drawn, &mut d).expect("copies");
        d.flush().expect("flushes");
        i2c.done();
    }))
    .is_ok()
}

/// Whether an SPI mock that expects the update of `expected` (data bytes MSB first or
/// not) takes the update the Sharp driver writes for `drawn`: its first update after
/// `sharp_display` (VCOM bit 0).
fn sharp_mock_takes(expected: &SharpFb, msb_first: bool, drawn: &SharpFb) -> bool {
    catch_unwind(AssertUnwindSafe(|| {
        let mut spi = SpiMock::new(&expect_sharp(expected, false, msb_first));
        let mut d = Box::new(panels::sharp_display(spi.clone(), NoPin, NoPin));
        panels::copy_frame(drawn, &mut Sharp(&mut *d)).expect("copies");
        d.flush_buffer();
        spi.done();
    }))
    .is_ok()
}

/// The `render` command's `--hash` line for `obj` seen from `v` at `size`.
fn render_hash(obj: &std::path::Path, size: &str, v: &scenes::View) -> u64 {
    let xyz = |a: [f32; 3]| format!("{},{},{}", a[0], a[1], a[2]);
    let (fov, near, far) = (v.fov_deg.to_string(), v.near.to_string(), v.far.to_string());
    let obj = obj.to_str().expect("a UTF-8 path");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_render"))
        .args([
            obj,
            "--size",
            size,
            "--eye",
            &xyz(v.eye),
            "--target",
            &xyz(v.target),
        ])
        .args(["--fov", &fov, "--near", &near, "--far", &far, "--hash"])
        .output()
        .expect("runs render");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let hex = text
        .lines()
        .find_map(|l| l.strip_prefix("hash: "))
        .expect("a hash line");
    u64::from_str_radix(hex.trim(), 16).expect("hex")
}

/// The frames the bus tests decode against are the `render` command's frames:
/// every view of both examples has the hash `render --hash` prints for it (the
/// bracket written out as an OBJ file).
#[test]
fn reference_frames_are_render_hash() {
    let dir = std::env::temp_dir().join(format!("panel_bus_{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut text = String::new();
    for v in panel::VERTICES {
        text += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for w in panel::OFFSETS.windows(2) {
        let face = &panel::INDICES[w[0] as usize..w[1] as usize];
        let corners: Vec<String> = face.iter().map(|i| (i + 1).to_string()).collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    let bracket = dir.join("bracket.obj");
    std::fs::write(&bracket, text).expect("writes the OBJ");
    let panel_fbs = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let suzanne_fbs = std::sync::Arc::new(std::sync::Mutex::new(Vec::new()));
    let (p, s) = (panel_fbs.clone(), suzanne_fbs.clone());
    big_stack(move || panel_baked(|b| *p.lock().unwrap() = panel_frames(b)));
    big_stack(move || suzanne_baked(|b| *s.lock().unwrap() = suzanne_frames(b)));
    let suzanne_obj = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/embedded/models/suzanne.obj");
    for (n, fb) in panel_fbs.lock().unwrap().iter().enumerate() {
        let want = render_hash(&bracket, "128x64", &panel::view(n as u32));
        assert_eq!(fnv1a64(fb.as_bytes()), want, "panel frame {n}");
    }
    for (n, fb) in suzanne_fbs.lock().unwrap().iter().enumerate() {
        let want = render_hash(&suzanne_obj, "400x240", &suzanne::view(n as u32));
        assert_eq!(fnv1a64(fb.as_bytes()), want, "suzanne frame {n}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
