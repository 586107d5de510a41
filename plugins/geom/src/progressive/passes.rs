//! The order of collapses: passes that cost every edge, radix-sort the
//! costs into bands and collapse the cheap ones the pass has not touched.

use super::{CHECK_EVERY, Cancelled, Control, Simplifier, VertexSplit};
use crate::ids::{EdgeId, VertexId};

/// A pass's sort key packed in 8 bytes: the cost as `f32` bits (costs are
/// never negative, so their bits order as the costs do) above the edge
/// id. The exact cost is computed again when the edge's turn comes.
fn entry(cost: f32, e: EdgeId) -> u64 {
    ((cost.to_bits() as u64) << 32) | e.0 as u64
}

/// Cost bands of a pass, as upper bounds of the cost bits, cheapest
/// first: [`PASS_BANDS`] bands of about equal size up to [`PASS_SLACK`]
/// times the cost at [`PASS_QUANTILE`] of the keys (all keys when not
/// `limited`). From a histogram of the costs' top 16 bits (sign, exponent
/// and 7 mantissa bits: within 1 %), linear in the keys.
fn cost_bands(keys: &[u64], hist: &mut [u32], limited: bool) -> Vec<u32> {
    hist.fill(0);
    for &k in keys {
        hist[(k >> 48) as usize] += 1;
    }
    // The upper bound of the bucket where the running count passes `n`.
    let bucket_top = |n: usize| -> u32 {
        let mut sum = 0usize;
        for (b, &c) in hist.iter().enumerate() {
            sum += c as usize;
            if sum > n {
                return ((b as u32) << 16) | 0xffff;
            }
        }
        u32::MAX
    };
    let limit = if limited {
        let q = bucket_top((keys.len() as f64 * PASS_QUANTILE) as usize);
        (f32::from_bits(q) * PASS_SLACK).to_bits()
    } else {
        u32::MAX
    };
    let eligible: usize = hist[..=(limit >> 16) as usize]
        .iter()
        .map(|&c| c as usize)
        .sum();
    let mut bands: Vec<u32> = (1..PASS_BANDS)
        .map(|i| bucket_top(eligible * i / PASS_BANDS).min(limit))
        .collect();
    bands.push(limit);
    bands.dedup();
    bands
}

/// Each pass works through its cost bands one after the other, each in
/// edge order (memory order, so that neighbouring collapses share cache
/// lines): the sequence is cheapest first up to a band.
const PASS_BANDS: usize = 4;

/// A pass collapses edges up to this multiple of the cost at
/// [`PASS_QUANTILE`] of its sorted keys (meshoptimizer takes 1.5 at about
/// two thirds; a lower quantile keeps the sequence closer to cheapest
/// first at the price of more passes).
const PASS_SLACK: f32 = 1.5;

/// See [`PASS_SLACK`].
const PASS_QUANTILE: f64 = 0.5;

impl Simplifier<'_> {
    /// Collapses in passes until none is possible, appending the records
    /// (meshoptimizer's scheme, A. Kapoulkine, `simplifier.cpp`): each
    /// pass computes every edge's cost in edge order (memory order, so
    /// the costs stream through the cache), sorts the keys, and collapses
    /// cheapest first up to [`PASS_SLACK`] times the cost at
    /// [`PASS_QUANTILE`]; a collapse locks the kept vertex for the rest of
    /// the pass (its quadric and position changed, so its edges' keys are
    /// stale until the next pass costs them). Every other edge's key stays
    /// exact (a cost reads only its two vertices), and the fold-over test
    /// and the features are checked when the edge's turn comes, on the
    /// mesh as it is then. A pass that collapses nothing is followed by
    /// one without the cost limit; when that collapses nothing either,
    /// no collapse is left (refusals depend on the neighbourhood, so each
    /// pass tries every edge again).
    ///
    /// `control` is told the faces removed and asked whether to stop
    /// every [`CHECK_EVERY`] keys; `Err` when it says stop.
    pub(super) fn run(
        &mut self,
        out: &mut Vec<VertexSplit>,
        control: &mut Control,
    ) -> Result<(), Cancelled> {
        let mut keys: Vec<u64> = Vec::new();
        let mut hist = vec![0u32; 1 << 16];
        let mut touched: Vec<VertexId> = Vec::new();
        let mut limited = true;
        loop {
            keys.clear();
            for e in self.mesh.edges() {
                if let Some(&(cost, _, _)) = self.candidates(e).first() {
                    keys.push(entry(cost as f32, e));
                }
            }
            if keys.is_empty() {
                return Ok(());
            }
            let bands = cost_bands(&keys, &mut hist, limited);
            let before = out.len();
            let mut lower = None;
            for &upper in &bands {
                for (i, &k) in keys.iter().enumerate() {
                    if i % CHECK_EVERY == 0 {
                        control.collapsing(self.removed_faces)?;
                    }
                    let bits = (k >> 32) as u32;
                    if bits > upper || lower.is_some_and(|l| bits <= l) {
                        continue;
                    }
                    let e = EdgeId(k as u32);
                    if !self.mesh.is_edge(e) {
                        continue;
                    }
                    let [a, b] = self.mesh.edge_vertices(e);
                    if self.locked[a.index()] || self.locked[b.index()] {
                        continue;
                    }
                    for (cost, h, p) in self.candidates(e).iter() {
                        if !self.allowed(h, p) {
                            continue;
                        }
                        if let Some(split) = self.collapse(h, p, cost) {
                            self.locked[split.kept.index()] = true;
                            touched.push(split.kept);
                            self.removed_faces += split.triangles();
                            out.push(split);
                            break;
                        }
                    }
                }
                lower = Some(upper);
            }
            for v in touched.drain(..) {
                self.locked[v.index()] = false;
            }
            let progressed = out.len() > before;
            if !progressed && !limited {
                return Ok(());
            }
            limited = progressed;
        }
    }
}
