//! Choosing a set's splitter.

use crate::mesh::Mesh;
use crate::order::bsp::BspOptions;
use crate::order::plane::{Fate, Plane, Records, Tally};

/// Chooses the splitter of a set: among up to `options.candidates` records spread
/// evenly over the set (skipping those of zero normal), the lowest score
/// `split_weight * splits + |front - back|`, the earliest on a tie. If no candidate
/// has a normal, the first record that has one; if none has, record 0 (a node of
/// zero-normal fragments, which cover no pixels). Returns the splitter's surface (its
/// record word: a face, or a fan triangle of one, see
/// [`Record::fan`](crate::order::plane::Record::fan)) and plane:
/// every fragment of that surface in the set goes to the node (a face that is not
/// planar and kept whole, cut earlier, keeps its pieces together in its plane's node).
pub(super) fn choose_splitter(
    mesh: &Mesh<'_>,
    set: &[u32],
    count: usize,
    options: &BspOptions,
    tolerance_sq: f64,
    vertices: &[[f32; 3]],
) -> (u32, Plane) {
    let tries = usize::from(options.candidates.max(1));
    let weight = u64::from(options.split_weight);
    let mut best: Option<(u64, u32, Plane)> = None;
    let mut next_try = 0usize; // index j of the next candidate ordinal j * count / tries
    for (ordinal, (word, _)) in Records::new(set).enumerate() {
        if next_try >= tries {
            break;
        }
        if ordinal < next_try.saturating_mul(count) / tries {
            continue;
        }
        while next_try < tries && next_try.saturating_mul(count) / tries <= ordinal {
            next_try += 1;
        }
        let plane = Plane::of_record(mesh, word, tolerance_sq);
        if plane.is_degenerate() {
            continue;
        }
        let bound = best.as_ref().map_or(u64::MAX, |b| b.0);
        let (mut splits, mut front, mut back) = (0u64, 0u64, 0u64);
        for (other, idx) in Records::new(set) {
            match Tally::of(&plane, idx, vertices).fate(other == word) {
                Fate::Node => {}
                Fate::Front => front += 1,
                Fate::Back => back += 1,
                Fate::Split { .. } => {
                    splits += 1;
                    front += 1;
                    back += 1;
                }
            }
            if weight.saturating_mul(splits) >= bound {
                break;
            }
        }
        let score = weight
            .saturating_mul(splits)
            .saturating_add(front.abs_diff(back));
        if score < bound {
            best = Some((score, word, plane));
        }
    }
    if let Some((_, word, plane)) = best {
        return (word, plane);
    }
    let first_with_normal = Records::new(set)
        .map(|(word, _)| (word, Plane::of_record(mesh, word, tolerance_sq)))
        .find(|(_, plane)| !plane.is_degenerate());
    first_with_normal.unwrap_or_else(|| {
        let word = set.first().copied().unwrap_or(0);
        (word, Plane::of_record(mesh, word, tolerance_sq))
    })
}
