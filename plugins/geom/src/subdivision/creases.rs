//! The cage's subdivision tags: crease sharpness of edges (with tapers
//! along chains of edges), corner sharpness of vertices and holes.

use super::*;

/// The cage's subdivision tags, by the cage's ids: crease sharpness of
/// edges, corner sharpness of vertices (missing entries are 0, smooth;
/// values at or above [`INFINITE_SHARPNESS`] are infinitely sharp) and face
/// holes. Entries of elements that no longer exist are ignored.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Creases {
    /// Crease sharpness per edge (only values above 0 are stored).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub edges: BTreeMap<EdgeId, f64>,
    /// Corner sharpness per vertex (only values above 0 are stored).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub vertices: BTreeMap<VertexId, f64>,
    /// Faces that are holes (OpenSubdiv's face hole tag): a hole is refined
    /// like any face and its neighbours keep their shape, but it leaves no
    /// faces in the refined or limit surface.
    #[serde(default, skip_serializing_if = "BTreeSet::is_empty")]
    pub holes: BTreeSet<FaceId>,
    /// Chains of edges whose sharpness runs from a start to an end value
    /// along the chain ([`set_taper`](Self::set_taper)). An edge is in at
    /// most one chain, and then not in [`edges`](Self::edges).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tapers: Vec<CreaseTaper>,
}

/// A crease whose sharpness varies along a chain of edges (Rhino's tapered
/// SubD creases; OpenSubdiv has only per-edge sharpness): `start` at the
/// chain's first vertex, `end` at its last, linear in arc length between.
/// Each edge takes the value at its midpoint, measured along the chain when
/// the taper was set (so moving vertices later does not change it), and is
/// then subdivided with the ordinary semi-sharp rules.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CreaseTaper {
    /// The chain's edges in order, each with the arc-length fraction
    /// (0 at the start, 1 at the end) of its midpoint.
    pub edges: Vec<(EdgeId, f64)>,
    /// Sharpness at the chain's start.
    pub start: f64,
    /// Sharpness at the chain's end.
    pub end: f64,
}

impl CreaseTaper {
    /// The sharpness at arc-length fraction `t` (0 … 1) of the chain.
    pub fn sharpness_at(&self, t: f64) -> f64 {
        self.start + (self.end - self.start) * t
    }
}

/// Why [`Creases::set_taper`] refused a chain. The creases are unchanged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TaperError {
    /// No edges were given.
    #[error("a tapered crease needs at least one edge")]
    NoEdges,
    /// An edge id the mesh does not have.
    #[error("edge {edge} does not exist")]
    NoSuchEdge {
        /// The missing edge.
        edge: EdgeId,
    },
    /// The edges do not form one path or one loop (a vertex with three or
    /// more of them, or separate pieces).
    #[error("the edges do not form one chain (a path or a loop): {why}")]
    NotAChain {
        /// Which way they fail.
        why: &'static str,
    },
    /// The start vertex is not an end of the path (or not on the loop).
    #[error("vertex {vertex} is not an end of the chain")]
    NotAnEnd {
        /// The vertex given as the start.
        vertex: VertexId,
    },
    /// A sharpness that is negative or not finite.
    #[error("sharpness {0} is not a finite value of 0 or more")]
    BadSharpness(f64),
}

impl Creases {
    /// True when no edge or vertex has a sharpness entry.
    pub fn is_empty(&self) -> bool {
        self.edges.is_empty()
            && self.vertices.is_empty()
            && self.holes.is_empty()
            && self.tapers.is_empty()
    }
    /// True when face `f` is a hole.
    pub fn is_hole(&self, f: FaceId) -> bool {
        self.holes.contains(&f)
    }
    /// Makes face `f` a hole (`true`) or clears its hole (`false`).
    pub fn set_hole(&mut self, f: FaceId, hole: bool) {
        if hole {
            self.holes.insert(f);
        } else {
            self.holes.remove(&f);
        }
    }
    /// Sharpness of edge `e` (0 when unset): its own, or its value along a
    /// tapered chain.
    pub fn edge(&self, e: EdgeId) -> f64 {
        if let Some(&s) = self.edges.get(&e) {
            return s;
        }
        self.tapers
            .iter()
            .find_map(|t| {
                t.edges
                    .iter()
                    .find(|(te, _)| *te == e)
                    .map(|&(_, at)| t.sharpness_at(at))
            })
            .unwrap_or(0.0)
    }
    /// Every edge with a sharpness above 0, its own or from a taper.
    pub fn edge_sharpness(&self) -> BTreeMap<EdgeId, f64> {
        let mut out = self.edges.clone();
        for t in &self.tapers {
            for &(e, at) in &t.edges {
                let s = t.sharpness_at(at);
                if s > 0.0 {
                    out.insert(e, s);
                }
            }
        }
        out
    }
    /// Makes `edges` one tapered crease: sharpness `start` at vertex `from`
    /// (an end of the path the edges form, or any vertex of the loop they
    /// form), `end` at the other end, linear in arc length between (each
    /// edge takes the value at its midpoint, measured now). The edges leave
    /// any plain crease or other taper they were in; inverse: `set_edge`
    /// of each edge to its old value, or [`clear_taper`](Self::clear_taper).
    /// Complexity: O(edges · tapers).
    ///
    /// # Errors
    /// [`TaperError`] when the edges are none, missing, not one path or
    /// loop, `from` is not an end, or a sharpness is negative or not finite.
    pub fn set_taper(
        &mut self,
        mesh: &HalfEdgeMesh,
        edges: &[EdgeId],
        from: VertexId,
        start: f64,
        end: f64,
    ) -> Result<(), TaperError> {
        for s in [start, end] {
            if !s.is_finite() || s < 0.0 {
                return Err(TaperError::BadSharpness(s));
            }
        }
        let chain = order_chain(mesh, edges, from)?;
        let lengths: Vec<f64> = chain
            .iter()
            .map(|&e| {
                let [a, b] = mesh.edge_vertices(e);
                mesh.position(a).distance(mesh.position(b))
            })
            .collect();
        let total: f64 = lengths.iter().sum();
        let mut run = 0.0;
        let mut taper = CreaseTaper {
            edges: Vec::with_capacity(chain.len()),
            start,
            end,
        };
        for (&e, &l) in chain.iter().zip(&lengths) {
            let t = if total > 0.0 {
                (run + 0.5 * l) / total
            } else {
                0.5
            };
            run += l;
            taper.edges.push((e, t));
        }
        self.clear_taper(&chain);
        for e in &chain {
            self.edges.remove(e);
        }
        self.tapers.push(taper);
        Ok(())
    }
    /// Takes `edges` out of every taper (they become smooth unless they
    /// have a plain crease); tapers left without edges are removed.
    pub fn clear_taper(&mut self, edges: &[EdgeId]) {
        for t in &mut self.tapers {
            t.edges.retain(|(e, _)| !edges.contains(e));
        }
        self.tapers.retain(|t| !t.edges.is_empty());
    }
    /// Corner sharpness of vertex `v` (0 when unset).
    pub fn vertex(&self, v: VertexId) -> f64 {
        self.vertices.get(&v).copied().unwrap_or(0.0)
    }
    /// Sets (or with 0, clears) the sharpness of edge `e`.
    pub fn set_edge(&mut self, e: EdgeId, sharpness: f64) {
        self.clear_taper(&[e]);
        if sharpness > 0.0 {
            self.edges.insert(e, sharpness);
        } else {
            self.edges.remove(&e);
        }
    }
    /// Sets (or with 0, clears) the corner sharpness of vertex `v`.
    pub fn set_vertex(&mut self, v: VertexId, sharpness: f64) {
        if sharpness > 0.0 {
            self.vertices.insert(v, sharpness);
        } else {
            self.vertices.remove(&v);
        }
    }
    /// The creases whose elements are still alive in `mesh`.
    pub fn retain_live(&mut self, mesh: &HalfEdgeMesh) {
        self.edges.retain(|e, _| mesh.is_edge(*e));
        self.vertices.retain(|v, _| mesh.is_vertex(*v));
        self.holes.retain(|f| mesh.is_face(*f));
        for t in &mut self.tapers {
            t.edges.retain(|(e, _)| mesh.is_edge(*e));
        }
        self.tapers.retain(|t| !t.edges.is_empty());
    }
}

/// `edges` in order along the path or loop they form, starting at `from`.
fn order_chain(
    mesh: &HalfEdgeMesh,
    edges: &[EdgeId],
    from: VertexId,
) -> Result<Vec<EdgeId>, TaperError> {
    if edges.is_empty() {
        return Err(TaperError::NoEdges);
    }
    let mut at: BTreeMap<VertexId, Vec<EdgeId>> = BTreeMap::new();
    let mut unique = BTreeSet::new();
    for &e in edges {
        if !mesh.is_edge(e) {
            return Err(TaperError::NoSuchEdge { edge: e });
        }
        if unique.insert(e) {
            for v in mesh.edge_vertices(e) {
                at.entry(v).or_default().push(e);
            }
        }
    }
    if at.values().any(|es| es.len() > 2) {
        return Err(TaperError::NotAChain {
            why: "a vertex has three or more of them",
        });
    }
    let ends = at.values().filter(|es| es.len() == 1).count();
    let from_ok = match at.get(&from) {
        Some(es) => ends == 0 || es.len() == 1,
        None => false,
    };
    if !from_ok {
        return Err(TaperError::NotAnEnd { vertex: from });
    }
    let mut chain = Vec::with_capacity(unique.len());
    let mut v = from;
    let mut prev: Option<EdgeId> = None;
    while let Some(&e) = at[&v].iter().find(|&&e| Some(e) != prev) {
        if chain.first() == Some(&e) {
            break;
        }
        chain.push(e);
        prev = Some(e);
        let [a, b] = mesh.edge_vertices(e);
        v = if a == v { b } else { a };
    }
    if chain.len() != unique.len() {
        return Err(TaperError::NotAChain {
            why: "they fall into separate pieces",
        });
    }
    Ok(chain)
}
