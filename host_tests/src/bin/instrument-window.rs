//! `instrument-window`: a 128 x 64, 1-bpp panel demo animated in an
//! embedded-graphics-simulator window (SDL2), each frame drawn by the firmware's code:
//! the instrument panel (`examples/scenes/src/instrument.rs`, the bracket turning beside
//! its label and turn angle) or, with `--demo arm`, the robot arm
//! (`examples/scenes/src/arm.rs`, its joints moving; the window titled
//! `pbuffer arm demo`).
//!
//! ```text
//! cargo run --release -p host_tests --features simulator --bin instrument-window -- [flags]
//! ```
//!
//! Keys: Space pauses and resumes, Right and Left step one frame (and pause), Q or Escape
//! quits. After each frame is on the screen it prints `frame N hash=HEX` (N in
//! 0..36 for the instrument, 0..8 for the arm: the frame `instrument [--demo arm]
//! --frames N` draws; the FNV-1a 64 hash of the packed
//! frame, as the firmware prints it), and `paused frame N` when paused. Those lines are
//! what `scripts/simulator-check` waits for before it takes a screenshot.
//!
//! Exit status: 0 when quit; 2 on bad flags or when no window can be opened.

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser;
use embedded_graphics::pixelcolor::{BinaryColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    BinaryColorTheme, OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use host_tests::firmware::{instrument, scenes::fnv1a64, PanelDemo};
use host_tests::image::Look;
use host_tests::tools::cli::{one_line, parse_look};

/// The flags of `instrument-window`.
#[derive(Debug, Parser)]
#[command(
    name = "instrument-window",
    about = "A panel demo (128x64, 1 bpp) animated in a simulator window. \
             Keys: Space pause/resume, Right/Left step, Q or Escape quit.",
    disable_version_flag = true,
    args_override_self = true
)]
struct Flags {
    /// The demo: instrument | arm
    #[arg(long, default_value = "instrument")]
    demo: String,
    /// Each display pixel as an S x S block of the window (no pixel spacing)
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u16).range(1..=16))]
    scale: u16,
    /// Colours: lcd-white | lcd-green | lcd-blue | oled-white | oled-blue | paper
    #[arg(long, default_value = "oled-blue", value_parser = parse_look)]
    look: Look,
    /// Frames a second while running
    #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=60))]
    fps: u32,
    /// Start paused on frame 0
    #[arg(long)]
    paused: bool,
}

/// Draws frame `n` into `display`; returns the line to print once it is shown.
fn show(demo: &mut PanelDemo, n: u32, display: &mut SimulatorDisplay<BinaryColor>) -> String {
    let fb = demo.frame(n);
    let (w, h) = (instrument::WIDTH as u32, instrument::HEIGHT as u32);
    let pixels = (0..h).flat_map(|y| (0..w).map(move |x| (x, y)));
    let pixels = pixels.map(|(x, y)| {
        Pixel(
            Point::new(x as i32, y as i32),
            BinaryColor::from(fb.pixel(x, y)),
        )
    });
    match display.draw_iter(pixels) {
        Ok(()) => {}
        Err(never) => match never {},
    }
    format!("frame {n} hash={:016x}", fnv1a64(fb.as_bytes()))
}

/// As the `viewer`: without a display say so, and with only an X display keep SDL to it.
fn choose_video_driver() -> Result<(), String> {
    let set = |v: &str| std::env::var_os(v).is_some_and(|x| !x.is_empty());
    if !cfg!(all(unix, not(target_os = "macos"))) || set("SDL_VIDEODRIVER") {
        return Ok(());
    }
    match (set("DISPLAY"), set("WAYLAND_DISPLAY")) {
        (false, false) => Err("no display: DISPLAY and WAYLAND_DISPLAY are unset (on a machine without one, run it under xvfb-run)".into()),
        // Still one thread: nothing else reads the environment yet.
        (true, false) => {
            std::env::set_var("SDL_VIDEODRIVER", "x11");
            Ok(())
        }
        _ => Ok(()),
    }
}

fn run(flags: Flags) -> Result<(), String> {
    choose_video_driver()?;
    let size = Size::new(instrument::WIDTH as u32, instrument::HEIGHT as u32);
    let mut display = SimulatorDisplay::<BinaryColor>::new(size);
    let (off, on) = flags.look.colours();
    // No pixel spacing: at scale 1 and 2 the window is then pixel for pixel the PNG
    // `instrument --scale S` writes.
    let settings = OutputSettingsBuilder::new()
        .scale(u32::from(flags.scale))
        .pixel_spacing(0)
        .theme(BinaryColorTheme::Custom {
            color_off: Rgb888::new(off[0], off[1], off[2]),
            color_on: Rgb888::new(on[0], on[1], on[2]),
        })
        .build();
    let mut demo = PanelDemo::named(&flags.demo).map_err(|e| format!("--demo: {e}"))?;
    let frames = demo.frames();
    // The screenshot check finds the window by its title.
    let title = format!("pbuffer {} demo", demo.name());
    let mut window = Window::new(&title, &settings);
    window.set_max_fps(flags.fps);
    let (mut n, mut paused) = (0u32, flags.paused);
    let mut pending = Some(show(&mut demo, n, &mut display));
    let mut stdout = std::io::stdout();
    let mut say = |line: &str| {
        // A closed pipe is no reason to stop the window.
        let _ = writeln!(stdout, "{line}");
        let _ = stdout.flush();
    };
    loop {
        window.update(&display);
        if let Some(line) = pending.take() {
            say(&line);
        }
        let mut step = None;
        for ev in window.events() {
            match ev {
                SimulatorEvent::Quit => return Ok(()),
                SimulatorEvent::KeyDown { keycode, .. } => match keycode {
                    Keycode::Q | Keycode::ESCAPE => return Ok(()),
                    Keycode::SPACE => {
                        paused = !paused;
                        if paused {
                            say(&format!("paused frame {n}"));
                        }
                    }
                    Keycode::RIGHT => (paused, step) = (true, Some(1)),
                    Keycode::LEFT => (paused, step) = (true, Some(frames - 1)),
                    _ => {}
                },
                _ => {}
            }
        }
        if !paused {
            step = Some(1);
        }
        if let Some(k) = step {
            n = (n + k) % frames;
            pending = Some(show(&mut demo, n, &mut display));
        }
    }
}

fn main() -> ExitCode {
    let flags = match Flags::try_parse() {
        Ok(f) => f,
        Err(e) if !e.use_stderr() => {
            print!("{e}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("instrument-window: {}", one_line(&e));
            return ExitCode::from(2);
        }
    };
    // The simulator unwraps SDL's errors (no display, no video driver): one line, not a
    // backtrace.
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        let first = msg.lines().next().unwrap_or("");
        eprintln!("instrument-window: stopped: {first} (the window needs SDL2 and a display)");
        std::process::exit(2);
    }));
    match run(flags) {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("instrument-window: {msg}");
            ExitCode::from(2)
        }
    }
}
