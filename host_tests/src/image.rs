//! Images for people and hashes for machines.
//!
//! * [`write_packed_png`] writes a packed 1-bpp framebuffer (the layout of
//!   `pbuffer::PackedFramebuffer::as_bytes`: row-major, `ceil(width / 8)` bytes per row,
//!   MSB-first, bit set = pixel on) as a PNG, each pixel blown up to `scale x scale`.
//! * [`write_rgb_png`] does the same for an 8-bit RGB buffer (3 bytes per pixel, row-major).
//!
//! A picture of at most 256 colours (every frame of the project's tools) is written as
//! an indexed PNG, its palette the colours in order of first appearance, at 1, 2, 4 or 8
//! bits a pixel: the same pixels as an RGB PNG, a small fraction of its size.
//! * [`fnv1a64`] is the FNV-1a 64-bit hash of a byte slice, used to pin down a frame.
//!
//! Set pixels are drawn black on white (ink on paper), the way the line drawings of the
//! project are meant to look.

mod look;
pub use look::Look;

use std::fs::File;
use std::io::{self, BufWriter};
use std::path::Path;

/// Bytes per row of a packed 1-bpp buffer `width` pixels wide.
pub const fn packed_stride(width: usize) -> usize {
    width.div_ceil(8)
}

/// Is pixel `(x, y)` set in a packed 1-bpp buffer (row-major, MSB-first)?
///
/// Panics if the pixel lies outside the buffer.
pub fn packed_pixel(bytes: &[u8], width: usize, x: usize, y: usize) -> bool {
    assert!(x < width, "x = {x} outside width {width}");
    (bytes[y * packed_stride(width) + x / 8] >> (7 - x % 8)) & 1 != 0
}

/// Number of set pixels in a packed 1-bpp buffer (padding bits in the last byte of a
/// row are ignored).
pub fn count_set(bytes: &[u8], width: usize, height: usize) -> usize {
    let stride = packed_stride(width);
    check_packed_len(bytes, width, height);
    let full = width / 8;
    let rest = width % 8;
    let mut n = 0usize;
    for row in bytes.chunks_exact(stride).take(height) {
        n += row[..full]
            .iter()
            .map(|b| b.count_ones() as usize)
            .sum::<usize>();
        if rest != 0 {
            n += (row[full] & (0xFFu8 << (8 - rest))).count_ones() as usize;
        }
    }
    n
}

/// Number of pixels that differ between two packed buffers of the same size.
pub fn count_diff(a: &[u8], b: &[u8], width: usize, height: usize) -> usize {
    check_packed_len(a, width, height);
    check_packed_len(b, width, height);
    let x: Vec<u8> = a.iter().zip(b).map(|(p, q)| p ^ q).collect();
    count_set(&x, width, height)
}

fn check_packed_len(bytes: &[u8], width: usize, height: usize) {
    assert_eq!(
        bytes.len(),
        packed_stride(width) * height,
        "a packed {width}x{height} buffer has {} bytes",
        packed_stride(width) * height
    );
}

/// FNV-1a, 64-bit (offset basis 0xcbf29ce484222325, prime 0x100000001b3).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Expands a packed 1-bpp buffer to RGB: set pixels `on`, clear pixels `off`.
pub fn packed_to_rgb(
    bytes: &[u8],
    width: usize,
    height: usize,
    on: [u8; 3],
    off: [u8; 3],
) -> Vec<u8> {
    check_packed_len(bytes, width, height);
    let mut rgb = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            rgb.extend_from_slice(if packed_pixel(bytes, width, x, y) {
                &on
            } else {
                &off
            });
        }
    }
    rgb
}

/// Writes a packed 1-bpp buffer as a PNG, black ink on white, scaled by `scale` (>= 1).
pub fn write_packed_png(
    path: &Path,
    bytes: &[u8],
    width: usize,
    height: usize,
    scale: usize,
) -> io::Result<()> {
    let rgb = packed_to_rgb(bytes, width, height, [0, 0, 0], [255, 255, 255]);
    write_rgb_png(path, &rgb, width, height, scale)
}

/// Writes an 8-bit RGB buffer (row-major, 3 bytes per pixel) as a PNG, scaled by
/// `scale` (>= 1): each pixel becomes a `scale x scale` block. Indexed when the
/// picture has at most 256 colours, RGB otherwise; decoded, the same pixels.
pub fn write_rgb_png(
    path: &Path,
    rgb: &[u8],
    width: usize,
    height: usize,
    scale: usize,
) -> io::Result<()> {
    if scale == 0 {
        return Err(io::Error::new(io::ErrorKind::InvalidInput, "scale 0"));
    }
    if rgb.len() != width * height * 3 {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "an RGB {width}x{height} buffer has {} bytes, not {}",
                width * height * 3,
                rgb.len()
            ),
        ));
    }
    let (sw, sh) = (width * scale, height * scale);
    let too_big = || io::Error::new(io::ErrorKind::InvalidInput, "image too large");
    let mut out = Vec::with_capacity(sw * sh * 3);
    for row in rgb.chunks_exact(width * 3).take(height) {
        let start = out.len();
        for px in row.chunks_exact(3) {
            for _ in 0..scale {
                out.extend_from_slice(px);
            }
        }
        for _ in 1..scale {
            out.extend_from_within(start..start + sw * 3);
        }
    }
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir)?;
        }
    }
    let file = BufWriter::new(File::create(path)?);
    let mut enc = png::Encoder::new(
        file,
        u32::try_from(sw).map_err(|_| too_big())?,
        u32::try_from(sh).map_err(|_| too_big())?,
    );
    enc.set_compression(png::Compression::Best);
    let data = match indexed(&out, sw) {
        Some(Indexed {
            palette,
            depth,
            rows,
        }) => {
            enc.set_color(png::ColorType::Indexed);
            enc.set_depth(depth);
            enc.set_palette(palette);
            rows
        }
        None => {
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            out
        }
    };
    let mut w = enc.write_header().map_err(io::Error::other)?;
    w.write_image_data(&data).map_err(io::Error::other)?;
    w.finish().map_err(io::Error::other)?;
    Ok(())
}

/// An RGB image as palette indices: the colours in order of first appearance and
/// the rows packed at the smallest bit depth that holds their indices.
struct Indexed {
    palette: Vec<u8>,
    depth: png::BitDepth,
    rows: Vec<u8>,
}

/// The image `rgb` (`width` pixels a row) as palette indices, when it has at most
/// 256 colours; the decoded pixels are the very same.
fn indexed(rgb: &[u8], width: usize) -> Option<Indexed> {
    if rgb.is_empty() || width == 0 {
        return None;
    }
    let mut colours: Vec<[u8; 3]> = Vec::new();
    let mut index = Vec::with_capacity(rgb.len() / 3);
    let mut last: Option<([u8; 3], u8)> = None;
    for px in rgb.chunks_exact(3) {
        let c = [px[0], px[1], px[2]];
        let k = match last {
            Some((lc, lk)) if lc == c => lk,
            _ => {
                let k = match colours.iter().position(|&p| p == c) {
                    Some(k) => k,
                    None if colours.len() < 256 => {
                        colours.push(c);
                        colours.len() - 1
                    }
                    None => return None,
                };
                let k = u8::try_from(k).ok()?;
                last = Some((c, k));
                k
            }
        };
        index.push(k);
    }
    let (depth, bits) = match colours.len() {
        0..=2 => (png::BitDepth::One, 1),
        3..=4 => (png::BitDepth::Two, 2),
        5..=16 => (png::BitDepth::Four, 4),
        _ => (png::BitDepth::Eight, 8),
    };
    let per_byte = 8 / bits;
    let mut rows = Vec::with_capacity(index.len() / per_byte + index.len() / width + 1);
    for row in index.chunks(width) {
        for group in row.chunks(per_byte) {
            let mut byte = 0u8;
            for (j, &k) in group.iter().enumerate() {
                byte |= k << (8 - bits * (j + 1));
            }
            rows.push(byte);
        }
    }
    Some(Indexed {
        palette: colours.concat(),
        depth,
        rows,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv_known_values() {
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
    }

    #[test]
    fn packed_pixels_and_counts() {
        // 10 px wide: 2 bytes per row; padding bits must be ignored.
        let bytes = [0b1000_0000, 0b0111_1111, 0b0000_0001, 0b1100_0000];
        assert!(packed_pixel(&bytes, 10, 0, 0));
        assert!(packed_pixel(&bytes, 10, 9, 0));
        assert!(!packed_pixel(&bytes, 10, 8, 0));
        assert!(packed_pixel(&bytes, 10, 7, 1));
        assert_eq!(count_set(&bytes, 10, 2), 1 + 1 + 1 + 2);
        assert_eq!(count_diff(&bytes, &[0; 4], 10, 2), 5);
    }

    #[test]
    fn png_round_trip_size() {
        let dir = std::env::temp_dir().join(format!("pbuffer-image-{}", std::process::id()));
        let p = dir.join("t.png");
        write_packed_png(&p, &[0xF0, 0x0F], 8, 2, 3).unwrap();
        let mut dec = png::Decoder::new(File::open(&p).unwrap());
        dec.set_transformations(png::Transformations::EXPAND);
        let mut r = dec.read_info().unwrap();
        assert_eq!(r.info().color_type, png::ColorType::Indexed);
        assert_eq!(r.info().bit_depth, png::BitDepth::One);
        let mut buf = vec![0; r.output_buffer_size()];
        let info = r.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (24, 6));
        assert_eq!(&buf[..3], &[0, 0, 0]); // (0,0) set: black
        assert_eq!(&buf[12 * 3..12 * 3 + 3], &[255, 255, 255]); // (4,0) clear: white
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn indexed_when_few_colours_and_pixels_unchanged() {
        let dir = std::env::temp_dir().join(format!("pbuffer-indexed-{}", std::process::id()));
        let p = dir.join("t.png");
        // 5 colours (4-bit indices) and 300 colours (RGB): decoded, the same pixels.
        for (colours, kind) in [(5u32, png::ColorType::Indexed), (300, png::ColorType::Rgb)] {
            let (w, h) = (7usize, 50usize);
            let rgb: Vec<u8> = (0..w * h)
                .flat_map(|i| {
                    let c = (i as u32 * 7) % colours;
                    [(c % 256) as u8, (c / 256) as u8, 9]
                })
                .collect();
            write_rgb_png(&p, &rgb, w, h, 2).unwrap();
            let mut dec = png::Decoder::new(File::open(&p).unwrap());
            dec.set_transformations(png::Transformations::EXPAND);
            let mut r = dec.read_info().unwrap();
            assert_eq!(r.info().color_type, kind);
            let mut buf = vec![0; r.output_buffer_size()];
            r.next_frame(&mut buf).unwrap();
            for y in 0..2 * h {
                for x in 0..2 * w {
                    let (a, b) = ((y * 2 * w + x) * 3, ((y / 2) * w + x / 2) * 3);
                    assert_eq!(buf[a..a + 3], rgb[b..b + 3], "({x}, {y})");
                }
            }
        }
        std::fs::remove_dir_all(dir).ok();
    }
}
