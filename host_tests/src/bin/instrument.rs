//! `instrument`: frames of a 128 x 64, 1-bpp panel demo drawn on the host with the
//! firmware's code, written side by side as one PNG: the instrument panel
//! (`examples/scenes/src/instrument.rs`, the bracket turning beside its label and turn
//! angle) or, with `--demo arm`, the robot arm (`examples/scenes/src/arm.rs`).
//!
//! ```text
//! cargo run --release -p host_tests --bin instrument -- --frames 0,4,8 --out docs/instrument.png
//! cargo run --release -p host_tests --bin instrument -- --demo arm --frames 0,7 --out docs/arm.png
//! ```
//!
//! Prints `frame DEMO N hash=HEX` for each frame (the FNV-1a 64 hash of the packed
//! frame, as the firmware example `instrument` or `arm` prints it). At `--scale 2` with one frame
//! the PNG is pixel for pixel the `instrument-window` simulator window of the same look
//! (`scripts/simulator-check` compares them). Exit status: 0 ok, 2 bad flags or an
//! unwritable file.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use host_tests::firmware::{frames_rgb, instrument, scenes::fnv1a64, PanelDemo};
use host_tests::image::write_rgb_png;
use host_tests::image::Look;
use host_tests::tools::cli::{one_line, parse_look};

/// The flags of `instrument`.
#[derive(Debug, Parser)]
#[command(
    name = "instrument",
    about = "Frames of a panel demo (128x64, 1 bpp) side by side in a PNG.",
    disable_version_flag = true,
    args_override_self = true
)]
struct Flags {
    /// The demo: instrument | arm
    #[arg(long, default_value = "instrument")]
    demo: String,
    /// Frame numbers, comma-separated (instrument: the part turns 10 degrees a frame)
    #[arg(long, value_delimiter = ',', default_value = "0")]
    frames: Vec<u32>,
    /// Each display pixel as an S x S block (from 3 up with a faint pixel grid)
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u16).range(1..=16))]
    scale: u16,
    /// Colours: lcd-white | lcd-green | lcd-blue | oled-white | oled-blue | paper
    #[arg(long, default_value = "oled-blue", value_parser = parse_look)]
    look: Look,
    /// Display pixels of glass between two frames
    #[arg(long, default_value_t = 4)]
    gap: u16,
    /// The PNG to write (none: only the hashes)
    #[arg(long)]
    out: Option<PathBuf>,
}

fn main() -> ExitCode {
    let flags = match Flags::try_parse() {
        Ok(f) => f,
        Err(e) if !e.use_stderr() => {
            print!("{e}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("instrument: {}", one_line(&e));
            return ExitCode::from(2);
        }
    };
    let mut demo = match PanelDemo::named(&flags.demo) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("instrument: --demo: {e}");
            return ExitCode::from(2);
        }
    };
    let frames: Vec<_> = flags.frames.iter().map(|&n| demo.frame(n)).collect();
    for (n, fb) in flags.frames.iter().zip(&frames) {
        let name = demo.name();
        println!("frame {name} {n} hash={:016x}", fnv1a64(fb.as_bytes()));
    }
    if let Some(path) = &flags.out {
        let refs: Vec<&instrument::Frame> = frames.iter().map(|f| &**f).collect();
        let (rgb, w, h) = frames_rgb(
            &refs,
            flags.look,
            usize::from(flags.scale),
            usize::from(flags.gap),
        );
        if let Err(e) = write_rgb_png(path, &rgb, w, h, 1) {
            eprintln!("instrument: --out: cannot write {}: {e}", path.display());
            return ExitCode::from(2);
        }
    }
    ExitCode::SUCCESS
}
