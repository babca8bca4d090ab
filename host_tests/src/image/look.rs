//! The colour scheme of the PNG (`--look`), shared with the `viewer` window.

/// The colour scheme of the PNG.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Look {
    /// A reflective memory LCD: grey-green glass, near-black pixels (the default).
    #[default]
    LcdWhite,
    /// Green glass, dark pixels.
    LcdGreen,
    /// Blue glass, white pixels.
    LcdBlue,
    /// White pixels on black.
    OledWhite,
    /// Cyan pixels on dark blue.
    OledBlue,
    /// Black ink on white paper, no pixel grid.
    Paper,
}

impl Look {
    /// Off and on colours (RGB) of the look, shared by `render`'s PNG and the `viewer`
    /// window so that a screenshot of one can be compared with the other.
    pub fn colours(self) -> ([u8; 3], [u8; 3]) {
        match self {
            // A reflective memory LCD: grey-green glass, near-black pixels.
            Look::LcdWhite => ([214, 219, 205], [38, 42, 48]),
            Look::LcdGreen => ([120, 185, 50], [32, 32, 32]),
            Look::LcdBlue => ([70, 80, 230], [230, 230, 255]),
            Look::OledWhite => ([20, 20, 20], [255, 255, 255]),
            Look::OledBlue => ([0, 20, 40], [0, 210, 255]),
            Look::Paper => ([255, 255, 255], [0, 0, 0]),
        }
    }
}
