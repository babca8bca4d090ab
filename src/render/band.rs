//! The face ids of one band of rows ([`IdBand`]): what every engine leaves for the
//! line pass and the output of a band.

/// Face ids of one band of rows, plus an apron of one row above and below (inside
/// the frame) so that the line test can look at a pixel's vertical neighbour
/// whatever the band height.
#[derive(Debug)]
pub(crate) struct IdBand<'s> {
    /// 0 for no face, else 1 + face index.
    pub ids: &'s mut [u16],
    pub width: u16,
    /// The band's own rows: `top .. top + rows`.
    pub top: u16,
    pub rows: u16,
    /// The rows held: `first .. first + held`, the own rows and the apron.
    pub first: u16,
    pub held: u16,
}

impl<'s> IdBand<'s> {
    /// An empty band over `ids`, `width` pixels wide.
    pub fn new(ids: &'s mut [u16], width: u16) -> Self {
        Self {
            ids,
            width,
            top: 0,
            rows: 0,
            first: 0,
            held: 0,
        }
    }

    /// Rows of storage a band of `rows` own rows needs in a frame `height` high.
    pub fn rows_needed(rows: u16, height: u16) -> u16 {
        if rows >= height {
            height
        } else {
            rows + 2
        }
    }

    /// Moves to the band of rows `top .. top + rows` of a frame `height` high.
    /// Rows held both before and after keep their ids (moved to their new place);
    /// returns the first row that was not held before.
    pub fn advance(&mut self, top: u16, rows: u16, height: u16) -> u16 {
        let (old_first, old_end) = (self.first, self.first + self.held);
        self.top = top;
        self.rows = rows;
        self.first = top.saturating_sub(1);
        self.held = (top + rows + 1).min(height) - self.first;
        let w = usize::from(self.width);
        if old_first <= self.first && self.first < old_end {
            let from = usize::from(self.first - old_first) * w;
            let to = usize::from(old_end - old_first) * w;
            if from < to && to <= self.ids.len() {
                self.ids.copy_within(from..to, 0);
            }
            old_end
        } else {
            self.first
        }
    }

    /// Index of pixel (x, y) in the band's buffers, if held (apron included).
    pub fn index(&self, x: u16, y: u16) -> Option<usize> {
        let row = y.checked_sub(self.first).filter(|r| *r < self.held)?;
        (x < self.width).then(|| usize::from(row) * usize::from(self.width) + usize::from(x))
    }

    /// The face id at pixel (x, y), 0 when none or not held.
    pub fn id(&self, x: u16, y: u16) -> u16 {
        self.index(x, y)
            .and_then(|i| self.ids.get(i))
            .copied()
            .unwrap_or(0)
    }

    /// The ids of row `y`, when held.
    pub fn row_mut(&mut self, y: u16) -> Option<&mut [u16]> {
        let start = self.index(0, y)?;
        self.ids.get_mut(start..start + usize::from(self.width))
    }

    /// The ids of row `y`, empty when not held.
    pub fn row(&self, y: u16) -> &[u16] {
        self.index(0, y)
            .and_then(|start| self.ids.get(start..start + usize::from(self.width)))
            .unwrap_or(&[])
    }
}
