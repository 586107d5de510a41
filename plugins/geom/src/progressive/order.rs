//! The order of collapses: cheapest first, by a priority queue whose
//! keys are brought up to date around every collapse (Garland and
//! Heckbert's greedy order).

use super::{CHECK_EVERY, Cancelled, Control, Simplifier, VertexSplit};
use crate::ids::{EdgeId, VertexId};
use radix_heap::RadixHeapMap;

/// The bits a cost is queued by: the cost as `f32` (costs are never
/// negative, so their bits order as the costs do). The exact cost is
/// computed again when the edge's turn comes.
fn cost_bits(cost: f64) -> u32 {
    (cost as f32).to_bits()
}

/// No key of this edge is in the queue.
const NOT_QUEUED: u32 = u32::MAX;

/// The queue of collapses, cheapest first: a radix heap (Ahuja, Mehlhorn,
/// Orlin and Tarjan 1990), whose pushes are appends to one of 33 buckets
/// and whose pops redistribute one bucket, instead of a binary heap's
/// walk down a tree of millions of keys. A radix heap is monotone: no key
/// may be cheaper than the last one taken. A collapse can make an edge
/// cheaper than that; such a key is queued at the last cost taken, so it
/// comes next, which is where the greedy order puts it. Of equal keys the
/// last pushed comes first, so ties (flat and symmetric parts) go on
/// where the last collapse was; on the decimation table of issue 35 this
/// closed two gaps the binary heap's order by edge id left open.
struct Queue {
    /// Keyed by the cost bits inverted (the crate's heap gives the
    /// greatest first); each item is the edge with the bits it was costed
    /// at.
    heap: RadixHeapMap<u32, (u32, EdgeId)>,
}

impl Queue {
    fn new() -> Self {
        Queue {
            heap: RadixHeapMap::new(),
        }
    }
    fn push(&mut self, bits: u32, e: EdgeId) {
        let key = !bits;
        let key = self.heap.top().map_or(key, |top| key.min(top));
        self.heap.push(key, (bits, e));
    }
    /// The cheapest edge, with the cost bits it was queued with.
    fn pop(&mut self) -> Option<(u32, EdgeId)> {
        self.heap.pop().map(|(_, item)| item)
    }
}

impl Simplifier<'_> {
    /// Collapses cheapest first until none is possible, appending the
    /// records (Garland and Heckbert 1997, §4: a heap of edge costs,
    /// updated around each collapse). Keys are quadric errors, lower
    /// bounds of the costs: the shape penalty
    /// ([`shaped`](Simplifier::shaped)) is computed when an edge comes
    /// up, and the edge goes back with its full cost when that is above
    /// its key (lazy evaluation: the penalty is computed for the edges
    /// that come up, not for every edge a collapse touches). The queue holds at most one live
    /// key per edge (`queued[e]`, the cost bits it was pushed with; older
    /// keys are skipped when they come up). After a collapse the edges at
    /// the kept vertex are costed again (its quadric and position
    /// changed), so are the edges between its neighbours (the shapes of
    /// the triangles they would leave changed; vcglib's `UpdateHeap` does
    /// the same), and the other edges at its neighbours that were refused
    /// and left the queue go back in (the fold-over test reads the faces
    /// around their ends, which the collapse changed). When the queue is
    /// empty, every edge is costed once more and the run repeats until a
    /// round collapses nothing (refusals depend on the neighbourhood).
    ///
    /// `control` is told the faces removed and asked whether to stop
    /// every [`CHECK_EVERY`] keys; `Err` when it says stop.
    pub(super) fn run(
        &mut self,
        out: &mut Vec<VertexSplit>,
        control: &mut Control,
    ) -> Result<(), Cancelled> {
        let mut queued = vec![NOT_QUEUED; self.mesh.edge_capacity()];
        let mut ring: Vec<VertexId> = Vec::new();
        let mut popped = 0usize;
        loop {
            let mut heap = Queue::new();
            for e in self.mesh.edges() {
                if let Some(&(cost, _, _)) = self.candidates(e).first() {
                    queued[e.index()] = cost_bits(cost);
                    heap.push(cost_bits(cost), e);
                }
            }
            let before = out.len();
            while let Some((key_bits, e)) = heap.pop() {
                popped += 1;
                if popped.is_multiple_of(CHECK_EVERY) {
                    control.collapsing(self.removed_faces)?;
                }
                if !self.mesh.is_edge(e) || queued[e.index()] != key_bits {
                    continue;
                }
                // The key was the quadric error, a lower bound; the cost
                // with the shape penalty is computed only now, and the edge
                // waits again when it is no longer the cheapest.
                let shaped = self.shaped(self.candidates(e));
                let Some(&(cost, _, _)) = shaped.first() else {
                    queued[e.index()] = NOT_QUEUED;
                    continue;
                };
                let bits = cost_bits(cost);
                if bits > key_bits {
                    queued[e.index()] = bits;
                    heap.push(bits, e);
                    continue;
                }
                queued[e.index()] = NOT_QUEUED;
                let mut done = None;
                for (cost, h, p) in shaped.iter() {
                    if !self.allowed(h, p) {
                        continue;
                    }
                    if let Some(split) = self.collapse(h, p, cost) {
                        done = Some(split);
                        break;
                    }
                }
                let Some(split) = done else { continue };
                let kept = split.kept;
                self.removed_faces += split.triangles();
                out.push(split);
                ring.clear();
                for o in self.mesh.vertex_outgoing(kept) {
                    ring.push(self.mesh.target(o));
                    self.requeue(o.edge(), &mut queued, &mut heap);
                }
                for (i, &u) in ring.iter().enumerate() {
                    for o in self.mesh.vertex_outgoing(u) {
                        let f = o.edge();
                        // A link edge once, from its end earlier in the ring.
                        let link = ring[i + 1..].contains(&self.mesh.target(o));
                        if link || queued[f.index()] == NOT_QUEUED {
                            self.requeue(f, &mut queued, &mut heap);
                        }
                    }
                }
            }
            if out.len() == before {
                return Ok(());
            }
        }
    }

    /// Costs `e` again and queues its key (none when no collapse of it is
    /// possible).
    fn requeue(&self, e: EdgeId, queued: &mut [u32], heap: &mut Queue) {
        match self.candidates(e).first() {
            Some(&(cost, _, _)) => {
                let bits = cost_bits(cost);
                if queued[e.index()] != bits {
                    queued[e.index()] = bits;
                    heap.push(bits, e);
                }
            }
            None => queued[e.index()] = NOT_QUEUED,
        }
    }
}
