//! `viewer`: the rotating-model demo in an embedded-graphics-simulator window (SDL2), drawn
//! by the library through `host_tests::pipeline::render_frame` in a 1-bit look.
//!
//! ```text
//! cargo run --release -p host_tests --features simulator --bin viewer -- [SCENE.obj] [flags]
//! ```
//!
//! It takes `render`'s scene and view flags (`--size`, camera, `--mode`, `--engine`,
//! `--look`, `--scale`, ...; not the output flags), so its first frame is the frame
//! `render` makes for the same flags. Keys: arrows turn the camera about the model,
//! +/- zoom, M cycles the modes, E cycles the engines, R resets the view, Q or Escape
//! quits.
//!
//! After each frame is on the screen it prints one line,
//! `frame N hash=HEX render: FLAGS`: the FNV-1a 64 hash of the packed frame (as
//! `render --hash` prints it) and the `render` flags that give exactly this view. That
//! line is what `scripts/simulator-check` waits for before it takes a screenshot.
//!
//! Exit status: 0 when quit; 2 on bad flags or scene, or when no window can be opened
//! (one line on stderr).

use std::io::Write as _;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::{BinaryColor, Rgb888};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::sdl2::Keycode;
use embedded_graphics_simulator::{
    BinaryColorTheme, OutputSettingsBuilder, SimulatorDisplay, SimulatorEvent, Window,
};
use host_tests::frame::{MeshData, RenderSpec};
use host_tests::image::{fnv1a64, packed_pixel};
use host_tests::obj::load_scene;
use host_tests::pipeline::render_frame;
use host_tests::tools::cli::{parse_args, Options};
use host_tests::tools::orbit::{
    engine_name, mode_name, next_mode, other_engine, render_flags, Orbit, STEP_DEG, ZOOM_STEP,
};

/// The window title; the screenshot check finds the window by it.
const TITLE: &str = "pbuffer viewer";

const USAGE: &str = "\
usage: viewer [SCENE.obj] [render's scene, camera, rendering and look flags]
  opens a window (SDL2) showing the model as `render` draws it for the same flags
keys: arrows turn about the model, + and - zoom, M next mode, E next engine,
      R reset the view, Q or Escape quit";

/// What a key asks for.
enum Action {
    Redraw,
    Quit,
    Nothing,
}

struct Viewer {
    mesh: MeshData,
    orbit: Orbit,
    spec: RenderSpec,
    o: Options,
    frames: u64,
}

impl Viewer {
    fn key(&mut self, k: Keycode) -> Action {
        match k {
            Keycode::LEFT => self.orbit.turn(-STEP_DEG),
            Keycode::RIGHT => self.orbit.turn(STEP_DEG),
            Keycode::UP => self.orbit.tilt(STEP_DEG),
            Keycode::DOWN => self.orbit.tilt(-STEP_DEG),
            // `=` is the unshifted `+` on most layouts.
            Keycode::PLUS | Keycode::EQUALS | Keycode::KP_PLUS => self.orbit.magnify(ZOOM_STEP),
            Keycode::MINUS | Keycode::KP_MINUS => self.orbit.magnify(1.0 / ZOOM_STEP),
            Keycode::M => self.spec.mode = next_mode(self.spec.mode),
            Keycode::E => self.spec.engine = other_engine(self.spec.engine),
            Keycode::R => self.orbit.reset(),
            Keycode::Q | Keycode::ESCAPE => return Action::Quit,
            _ => return Action::Nothing,
        }
        Action::Redraw
    }

    /// Renders the current view into `display`; returns the line to print once it is
    /// on the screen. A view the library rejects keeps the previous picture and says why.
    fn draw(&mut self, display: &mut SimulatorDisplay<BinaryColor>) -> Option<String> {
        let cam = self.orbit.camera();
        let frame = match render_frame(&self.mesh, &cam, &self.spec) {
            Ok(f) => f,
            Err(e) => {
                eprintln!("viewer: this view cannot be drawn ({e}); keeping the last frame");
                return None;
            }
        };
        let w = frame.width;
        let pixels = (0..frame.height).flat_map(|y| (0..w).map(move |x| (x, y)));
        let pixels = pixels.map(|(x, y)| {
            let lit = packed_pixel(&frame.packed, w, x, y);
            Pixel(Point::new(x as i32, y as i32), BinaryColor::from(lit))
        });
        match display.draw_iter(pixels) {
            Ok(()) => {}
            Err(never) => match never {},
        }
        self.frames += 1;
        let flags = render_flags(&cam, &self.spec, self.o.look, self.o.scale).join(" ");
        Some(format!(
            "frame {} hash={:016x} mode={} engine={} render: {flags}",
            self.frames,
            fnv1a64(&frame.packed),
            mode_name(self.spec.mode),
            engine_name(self.spec.engine)
        ))
    }
}

/// When its display cannot be reached SDL falls back to other video drivers and may open a
/// window that nobody sees and no key reaches: without a display, say so; with only an X
/// display, keep SDL to it so that a wrong DISPLAY is an error. `SDL_VIDEODRIVER` set by
/// the user is their choice. (Linux and the BSDs; elsewhere SDL has one native driver.)
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

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let o = parse_args(&args)?;
    if o.help {
        println!("{USAGE}");
        return Ok(());
    }
    if o.out.is_some() || o.ids.is_some() || o.lines.is_some() || o.stats || o.hash {
        return Err(
            "--out, --ids, --lines, --stats and --hash are render's; the viewer writes no files"
                .into(),
        );
    }
    choose_video_driver()?;
    let (mesh, _) = load_scene(o.scene.as_deref())?;
    let orbit = Orbit::new(o.camera(&mesh)?, &mesh);
    let (w, h) = (o.spec.width, o.spec.height);
    let mut display = SimulatorDisplay::<BinaryColor>::new(Size::new(w as u32, h as u32));
    let (off, on) = o.look.colours();
    // No pixel spacing: at scale 1 and 2 the window is then pixel for pixel `render`'s PNG.
    let settings = OutputSettingsBuilder::new()
        .scale(o.scale as u32)
        .pixel_spacing(0)
        .theme(BinaryColorTheme::Custom {
            color_off: Rgb888::new(off[0], off[1], off[2]),
            color_on: Rgb888::new(on[0], on[1], on[2]),
        })
        .build();
    let mut window = Window::new(TITLE, &settings);
    // A still picture between keys: no need to spin faster on a shared machine.
    window.set_max_fps(30);
    let mut v = Viewer {
        mesh,
        orbit,
        spec: o.spec.clone(),
        o,
        frames: 0,
    };
    let mut pending = v.draw(&mut display);
    let mut stdout = std::io::stdout();
    loop {
        window.update(&display);
        if let Some(line) = pending.take() {
            // A closed pipe is no reason to stop the window.
            let _ = writeln!(stdout, "{line}");
            let _ = stdout.flush();
        }
        let mut redraw = false;
        for ev in window.events() {
            let action = match ev {
                SimulatorEvent::Quit => Action::Quit,
                SimulatorEvent::KeyDown { keycode, .. } => v.key(keycode),
                _ => Action::Nothing,
            };
            match action {
                Action::Quit => return Ok(()),
                Action::Redraw => redraw = true,
                Action::Nothing => {}
            }
        }
        if redraw {
            pending = v.draw(&mut display);
        }
    }
}

fn main() -> ExitCode {
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
        // The message names SDL's complaint, e.g. `"x11 not available"`.
        eprintln!("viewer: stopped: {first} (the window needs SDL2 and a display)");
        std::process::exit(2);
    }));
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("viewer: {msg}");
            ExitCode::from(2)
        }
    }
}
