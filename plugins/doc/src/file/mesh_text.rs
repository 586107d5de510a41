//! The mesh pools of a scene file, written and read without going through
//! the RON serializer number by number: they hold nearly all of a big
//! file's bytes.
//!
//! Version 3 stores a mesh in polygon form (`hedra_geom::PolygonData`):
//!
//! ```text
//! (
//!     positions: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), …],
//!     faces: [[0, 1, 2, 3], …],
//!     corner_halfedges: [(corner, half-edge), …],       // left out when empty
//!     vertex_halfedges: [(vertex, half-edge or -1), …], // left out when empty
//!     dead_vertices: […], dead_edges: […], dead_halfedges: [(o, n, p, f), …],
//!     dead_faces: […], dead_face_halfedges: […],        // each left out when empty
//! )
//! ```
//!
//! and the meshes that form cannot hold (faces with rings or without
//! edges, two edges between one pair of vertices) as records, the shape
//! versions 1 and 2 store every mesh in (`hedra_geom::MeshData`).
//!
//! Writing formats numbers with `zmij` (shortest round-trip floats, as
//! `{:?}`) and `itoa`. Reading has a fast path, [`prepare`]: the file's two
//! mesh lists (the scene's and the history's) are parsed by a small parser
//! made for exactly this grammar and cut out of the text before the RON
//! parser reads the rest. Whatever the fast parser does not expect (a
//! comment inside a number list, a field it does not know, a damaged
//! mesh) leaves the list to the RON parser and [`StoredMesh`]'s
//! `Deserialize`, which reads every form and reports errors with their line
//! and column.

use glam::DVec3;
use hedra_geom::{HalfEdgeMesh, LoopStart, MeshData, PolygonData};
use serde::Deserialize;
use std::borrow::Cow;

const NONE: u32 = u32::MAX;

// ----- writing ---------------------------------------------------------------

/// Appends numbers to a string, each formatted once.
struct Out<'a> {
    s: &'a mut String,
    floats: zmij::Buffer,
    ints: itoa::Buffer,
}

impl Out<'_> {
    fn f(&mut self, x: f64) {
        if x.is_nan() {
            // As the RON serializer writes it (`-NaN` for a negative NaN).
            self.s
                .push_str(if x.is_sign_negative() { "-NaN" } else { "NaN" });
        } else {
            self.s.push_str(self.floats.format(x));
        }
    }
    fn u(&mut self, x: u32) {
        self.s.push_str(self.ints.format(x));
    }
    /// A raw id with `u32::MAX` written as `-1`.
    fn id(&mut self, x: u32) {
        if x == NONE {
            self.s.push_str("-1");
        } else {
            self.u(x);
        }
    }
    fn list<T: Copy>(&mut self, items: &[T], mut each: impl FnMut(&mut Self, T)) {
        self.s.push('[');
        for (i, &x) in items.iter().enumerate() {
            if i > 0 {
                self.s.push_str(", ");
            }
            each(self, x);
        }
        self.s.push(']');
    }
    fn tuple<const N: usize>(&mut self, items: [u32; N], last_is_id: bool) {
        self.s.push('(');
        for (i, x) in items.into_iter().enumerate() {
            if i > 0 {
                self.s.push_str(", ");
            }
            if last_is_id && i + 1 == N {
                self.id(x);
            } else {
                self.u(x);
            }
        }
        self.s.push(')');
    }
}

/// How a mesh record is laid out: one field per line at this indentation
/// (the scene's pool), or all on one line (the history's pool).
#[derive(Clone, Copy)]
pub(super) enum Layout<'a> {
    /// Fields on their own lines, indented by the first string; the record's
    /// parentheses by the second.
    Lines(&'a str, &'a str),
    /// The whole record on one line.
    OneLine,
}

/// Appends one mesh record (without a trailing comma).
pub(super) fn write_mesh(s: &mut String, m: &HalfEdgeMesh, layout: Layout<'_>) {
    let mut out = Out {
        s,
        floats: zmij::Buffer::new(),
        ints: itoa::Buffer::new(),
    };
    let mut first = true;
    let mut field = |out: &mut Out<'_>, name: &str| {
        match layout {
            Layout::Lines(inner, _) => {
                out.s.push('\n');
                out.s.push_str(inner);
            }
            Layout::OneLine if !first => out.s.push_str(", "),
            Layout::OneLine => {}
        }
        first = false;
        out.s.push_str(name);
        out.s.push_str(": ");
    };
    let end_field = |out: &mut Out<'_>| {
        if let Layout::Lines(..) = layout {
            out.s.push(',');
        }
    };
    out.s.push('(');
    match m.polygon_data() {
        Some(d) => {
            field(&mut out, "positions");
            out.list(&d.positions, |o, p| {
                o.s.push('(');
                o.f(p.x);
                o.s.push_str(", ");
                o.f(p.y);
                o.s.push_str(", ");
                o.f(p.z);
                o.s.push(')');
            });
            end_field(&mut out);
            field(&mut out, "faces");
            out.s.push('[');
            for f in 0..d.face_capacity() {
                if f > 0 {
                    out.s.push_str(", ");
                }
                let corners = &d.corners[d.face_start[f] as usize..d.face_start[f + 1] as usize];
                out.list(corners, |o, v| o.u(v));
            }
            out.s.push(']');
            end_field(&mut out);
            let pairs = [
                ("corner_halfedges", &d.corner_halfedges, false),
                ("vertex_halfedges", &d.vertex_halfedges, true),
            ];
            for (name, list, id) in pairs {
                if !list.is_empty() {
                    field(&mut out, name);
                    out.list(list, |o, (a, b)| o.tuple([a, b], id));
                    end_field(&mut out);
                }
            }
            let dead = [
                ("dead_vertices", &d.dead_vertices),
                ("dead_edges", &d.dead_edges),
            ];
            for (name, list) in dead {
                if !list.is_empty() {
                    field(&mut out, name);
                    out.list(list, |o, x| o.u(x));
                    end_field(&mut out);
                }
            }
            if !d.dead_halfedges.is_empty() {
                field(&mut out, "dead_halfedges");
                out.list(&d.dead_halfedges, |o, r| o.tuple(r, false));
                end_field(&mut out);
            }
            let dead = [
                ("dead_faces", &d.dead_faces),
                ("dead_face_halfedges", &d.dead_face_halfedges),
            ];
            for (name, list) in dead {
                if !list.is_empty() {
                    field(&mut out, name);
                    out.list(list, |o, x| o.u(x));
                    end_field(&mut out);
                }
            }
        }
        None => {
            // Records, field by field as the RON serializer writes them.
            let d = MeshData::from(m.clone());
            let config = ron::ser::PrettyConfig::new()
                .depth_limit(0)
                .struct_names(false);
            let mut ron_field = |out: &mut Out<'_>, name: &str, text: String| {
                field(out, name);
                out.s.push_str(&text);
                end_field(out);
            };
            let text = |v: &dyn erased::Ser| v.ron(&config);
            ron_field(&mut out, "positions", text(&d.positions));
            ron_field(&mut out, "vertex_halfedge", text(&d.vertex_halfedge));
            ron_field(&mut out, "halfedges", text(&d.halfedges));
            ron_field(&mut out, "face_halfedge", text(&d.face_halfedge));
            for (name, list) in [
                ("dead_vertices", &d.dead_vertices),
                ("dead_edges", &d.dead_edges),
                ("dead_faces", &d.dead_faces),
            ] {
                if !list.is_empty() {
                    ron_field(&mut out, name, text(list));
                }
            }
            if !d.face_rings.is_empty() {
                ron_field(&mut out, "face_rings", text(&d.face_rings));
            }
            if !d.lone_vertex_faces.is_empty() {
                ron_field(&mut out, "lone_vertex_faces", text(&d.lone_vertex_faces));
            }
        }
    }
    if let Layout::Lines(_, outer) = layout {
        out.s.push('\n');
        out.s.push_str(outer);
    }
    out.s.push(')');
}

/// A small object-safe wrapper over `Serialize` for the record fields.
mod erased {
    pub(super) trait Ser {
        fn ron(&self, config: &ron::ser::PrettyConfig) -> String;
    }
    impl<T: serde::Serialize> Ser for T {
        fn ron(&self, config: &ron::ser::PrettyConfig) -> String {
            ron::ser::to_string_pretty(self, config.clone()).expect("mesh records serialise")
        }
    }
}

// ----- reading: every form, through serde ------------------------------------

/// A mesh of the pool as any version stores it, read and validated.
pub(super) struct StoredMesh(pub(super) HalfEdgeMesh);

/// Every field of both forms; which ones are present decides the form.
#[derive(Deserialize)]
struct MeshFields {
    positions: Vec<DVec3>,
    #[serde(default, deserialize_with = "present")]
    faces: Option<Vec<Vec<u32>>>,
    #[serde(default)]
    corner_halfedges: Vec<(u32, u32)>,
    #[serde(default)]
    vertex_halfedges: Vec<(u32, i64)>,
    #[serde(default)]
    dead_halfedges: Vec<(u32, u32, u32, u32)>,
    #[serde(default)]
    dead_face_halfedges: Vec<u32>,
    #[serde(default, deserialize_with = "present")]
    vertex_halfedge: Option<Vec<i64>>,
    #[serde(default, deserialize_with = "present")]
    halfedges: Option<Vec<(u32, u32, u32, i64)>>,
    #[serde(default, deserialize_with = "present")]
    face_halfedge: Option<Vec<u32>>,
    #[serde(default)]
    dead_vertices: Vec<u32>,
    #[serde(default)]
    dead_edges: Vec<u32>,
    #[serde(default)]
    dead_faces: Vec<u32>,
    #[serde(default)]
    face_rings: Vec<(u32, Vec<LoopStart>)>,
    #[serde(default)]
    lone_vertex_faces: Vec<(u32, u32)>,
}

/// A field that is there (`Some`) or left out (`None`, by its default),
/// written without `Some(…)`.
pub(super) fn present<'de, D: serde::Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

/// Why stored mesh fields do not make a mesh.
#[derive(Debug, thiserror::Error)]
enum FormError {
    #[error("a mesh has `faces` (polygon form) and records (`halfedges`, …) at once")]
    BothForms,
    #[error("missing field `{0}`")]
    Missing(&'static str),
    #[error("vertex half-edge {0} is out of range")]
    VertexHalfEdge(i64),
    #[error(transparent)]
    Mesh(#[from] hedra_geom::MeshDataError),
}

fn raw_id(x: i64) -> Result<u32, FormError> {
    match x {
        -1 => Ok(NONE),
        0..0xFFFF_FFFF => Ok(x as u32),
        _ => Err(FormError::VertexHalfEdge(x)),
    }
}

impl MeshFields {
    fn mesh(self) -> Result<HalfEdgeMesh, FormError> {
        let Some(faces) = self.faces else {
            let d = MeshData {
                positions: self.positions,
                vertex_halfedge: self
                    .vertex_halfedge
                    .ok_or(FormError::Missing("vertex_halfedge"))?,
                halfedges: self.halfedges.ok_or(FormError::Missing("halfedges"))?,
                face_halfedge: self
                    .face_halfedge
                    .ok_or(FormError::Missing("face_halfedge"))?,
                dead_vertices: self.dead_vertices,
                dead_edges: self.dead_edges,
                dead_faces: self.dead_faces,
                face_rings: self.face_rings,
                lone_vertex_faces: self.lone_vertex_faces,
            };
            return Ok(HalfEdgeMesh::try_from(d)?);
        };
        if self.vertex_halfedge.is_some()
            || self.halfedges.is_some()
            || self.face_halfedge.is_some()
            || !self.face_rings.is_empty()
            || !self.lone_vertex_faces.is_empty()
        {
            return Err(FormError::BothForms);
        }
        let mut face_start = Vec::with_capacity(faces.len() + 1);
        face_start.push(0u32);
        let mut corners = Vec::new();
        for f in faces {
            corners.extend_from_slice(&f);
            face_start.push(u32::try_from(corners.len()).unwrap_or(NONE));
        }
        let d = PolygonData {
            positions: self.positions,
            face_start,
            corners,
            corner_halfedges: self.corner_halfedges,
            vertex_halfedges: self
                .vertex_halfedges
                .into_iter()
                .map(|(v, h)| Ok((v, raw_id(h)?)))
                .collect::<Result<_, FormError>>()?,
            dead_vertices: self.dead_vertices,
            dead_edges: self.dead_edges,
            dead_halfedges: self
                .dead_halfedges
                .into_iter()
                .map(|(o, n, p, f)| [o, n, p, f])
                .collect(),
            dead_faces: self.dead_faces,
            dead_face_halfedges: self.dead_face_halfedges,
        };
        Ok(HalfEdgeMesh::try_from(d)?)
    }
}

impl<'de> Deserialize<'de> for StoredMesh {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        MeshFields::deserialize(d)?
            .mesh()
            .map(StoredMesh)
            .map_err(serde::de::Error::custom)
    }
}

// ----- reading: the fast path ---------------------------------------------------

/// A file's text with its mesh lists taken out where the fast parser read
/// them (each replaced by `[]` and the newlines it spanned, so the RON
/// parser's line numbers still point into the file).
pub(super) struct Prepared<'a> {
    /// The text for the RON parser.
    pub text: Cow<'a, str>,
    /// The scene's mesh pool, when the fast parser read it.
    pub scene_meshes: Option<Vec<HalfEdgeMesh>>,
    /// The history's own meshes, when the fast parser read them.
    pub history_meshes: Option<Vec<HalfEdgeMesh>>,
}

/// Finds the two mesh lists (`meshes` of the top-level struct and of its
/// `history`) and reads each with the fast parser; see the module docs.
pub(super) fn prepare(text: &str) -> Prepared<'_> {
    let mut spans: Vec<(usize, usize, Vec<HalfEdgeMesh>, bool)> = Vec::new();
    let mut c = Cursor {
        s: text,
        b: text.as_bytes(),
        i: 0,
    };
    // Any surprise ends the search; what was found so far is kept.
    let _ = (|| -> Option<()> {
        c.expect(b'(')?;
        loop {
            if c.eat(b')') {
                return Some(());
            }
            let name = c.ident()?;
            c.expect(b':')?;
            match name {
                "meshes" => {
                    if let Some(span) = c.mesh_list() {
                        spans.push((span.0, span.1, span.2, false));
                    } else {
                        c.skip_value()?;
                    }
                }
                "history" => {
                    c.ws();
                    if c.peek() == Some(b'(') {
                        c.i += 1;
                        loop {
                            if c.eat(b')') {
                                break;
                            }
                            let name = c.ident()?;
                            c.expect(b':')?;
                            match c.mesh_list_if(name == "meshes") {
                                // The rest of the history is the RON parser's.
                                Some(span) => {
                                    spans.push((span.0, span.1, span.2, true));
                                    return Some(());
                                }
                                None => c.skip_value()?,
                            }
                            if !c.eat(b',') {
                                c.expect(b')')?;
                                break;
                            }
                        }
                    } else {
                        c.skip_value()?;
                    }
                }
                _ => c.skip_value()?,
            }
            if !c.eat(b',') {
                c.expect(b')')?;
                return Some(());
            }
        }
    })();
    if spans.is_empty() {
        return Prepared {
            text: Cow::Borrowed(text),
            scene_meshes: None,
            history_meshes: None,
        };
    }
    let mut out = String::with_capacity(text.len().min(1 << 20));
    let mut at = 0;
    let (mut scene_meshes, mut history_meshes) = (None, None);
    for (start, end, meshes, in_history) in spans {
        out.push_str(&text[at..start]);
        out.push_str("[]");
        let newlines = text.as_bytes()[start..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        out.extend(std::iter::repeat_n('\n', newlines));
        at = end;
        if in_history {
            history_meshes = Some(meshes);
        } else {
            scene_meshes = Some(meshes);
        }
    }
    out.push_str(&text[at..]);
    Prepared {
        text: Cow::Owned(out),
        scene_meshes,
        history_meshes,
    }
}

/// A byte cursor over RON text, for exactly the grammar of mesh lists.
struct Cursor<'a> {
    /// The text, for slices that are already known to be UTF-8.
    s: &'a str,
    b: &'a [u8],
    i: usize,
}

impl<'a> Cursor<'a> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.i).copied()
    }

    /// Skips whitespace and comments (`//` lines, nested `/* */` blocks).
    fn ws(&mut self) {
        loop {
            while let Some(b' ' | b'\n' | b'\r' | b'\t') = self.peek() {
                self.i += 1;
            }
            if self.b[self.i.min(self.b.len())..].starts_with(b"//") {
                while let Some(b) = self.peek() {
                    self.i += 1;
                    if b == b'\n' {
                        break;
                    }
                }
            } else if self.b[self.i.min(self.b.len())..].starts_with(b"/*") {
                let mut depth = 0usize;
                while self.i < self.b.len() {
                    let rest = &self.b[self.i..];
                    if rest.starts_with(b"/*") {
                        depth += 1;
                        self.i += 2;
                    } else if rest.starts_with(b"*/") {
                        depth -= 1;
                        self.i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        self.i += 1;
                    }
                }
            } else {
                return;
            }
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        self.ws();
        if self.peek() == Some(c) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn expect(&mut self, c: u8) -> Option<()> {
        self.eat(c).then_some(())
    }

    fn ident(&mut self) -> Option<&'a str> {
        self.ws();
        let start = self.i;
        while let Some(b'a'..=b'z' | b'A'..=b'Z' | b'0'..=b'9' | b'_') = self.peek() {
            self.i += 1;
        }
        (self.i > start)
            .then(|| self.s.get(start..self.i))
            .flatten()
    }

    /// A plain decimal whole number.
    fn uint(&mut self) -> Option<u64> {
        self.ws();
        let start = self.i;
        let mut v: u64 = 0;
        while let Some(d @ b'0'..=b'9') = self.peek() {
            v = v.checked_mul(10)?.checked_add(u64::from(d - b'0'))?;
            self.i += 1;
        }
        // `1.0`, `1e3`, `0x1`, `1_000`: not this parser's.
        if self.i == start
            || matches!(
                self.peek(),
                Some(b'.' | b'e' | b'E' | b'_' | b'x' | b'b' | b'o' | b'u' | b'i')
            )
        {
            return None;
        }
        Some(v)
    }

    fn u32(&mut self) -> Option<u32> {
        u32::try_from(self.uint()?).ok()
    }

    /// A raw id, `-1` for none.
    fn id(&mut self) -> Option<u32> {
        self.ws();
        if self.peek() == Some(b'-') {
            self.i += 1;
            return (self.uint()? == 1).then_some(NONE);
        }
        let v = self.uint()?;
        (v < u64::from(NONE)).then_some(v as u32)
    }

    fn f64(&mut self) -> Option<f64> {
        self.ws();
        let start = self.i;
        let mut word = false;
        loop {
            match self.peek() {
                Some(b'0'..=b'9' | b'.' | b'-' | b'+' | b'e' | b'E') => {}
                Some(b'N' | b'a' | b'i' | b'n' | b'f') => word = true,
                _ => break,
            }
            self.i += 1;
        }
        // ASCII bytes were scanned: the slice is on character boundaries.
        let s = self.s.get(start..self.i)?;
        if !word {
            // Rust's grammar is RON's for plain decimals.
            return s.parse().ok();
        }
        // The words RON writes; others Rust would take ("infinity") are not RON.
        match s {
            "NaN" => Some(f64::NAN),
            "-NaN" => Some(-f64::NAN),
            "inf" => Some(f64::INFINITY),
            "-inf" => Some(f64::NEG_INFINITY),
            _ => None,
        }
    }

    /// `[item, item, …]` with an optional trailing comma.
    fn list(&mut self, mut item: impl FnMut(&mut Self) -> Option<()>) -> Option<()> {
        self.expect(b'[')?;
        loop {
            if self.eat(b']') {
                return Some(());
            }
            item(self)?;
            if !self.eat(b',') {
                return self.expect(b']');
            }
        }
    }

    /// `(a, b, …)` of `N` numbers read by `read`.
    fn tuple<const N: usize>(
        &mut self,
        mut read: impl FnMut(&mut Self, usize) -> Option<u32>,
    ) -> Option<[u32; N]> {
        self.expect(b'(')?;
        let mut out = [0u32; N];
        for (k, slot) in out.iter_mut().enumerate() {
            if k > 0 {
                self.expect(b',')?;
            }
            *slot = read(self, k)?;
        }
        self.eat(b',');
        self.expect(b')')?;
        Some(out)
    }

    fn u32_list(&mut self) -> Option<Vec<u32>> {
        let mut v = Vec::new();
        self.list(|c| {
            v.push(c.u32()?);
            Some(())
        })?;
        Some(v)
    }

    /// Reads `[mesh, …]` here when `wanted`; `None` (and the cursor back)
    /// when not wanted or not readable.
    fn mesh_list_if(&mut self, wanted: bool) -> Option<(usize, usize, Vec<HalfEdgeMesh>)> {
        if wanted { self.mesh_list() } else { None }
    }

    /// Reads `[mesh, …]`: its span in the text and the meshes, or `None`
    /// with the cursor where it was.
    fn mesh_list(&mut self) -> Option<(usize, usize, Vec<HalfEdgeMesh>)> {
        let back = self.i;
        self.ws();
        let start = self.i;
        let mut meshes = Vec::new();
        let ok = self.list(|c| {
            meshes.push(c.mesh()?);
            Some(())
        });
        if ok.is_none() {
            self.i = back;
            return None;
        }
        Some((start, self.i, meshes))
    }

    /// One mesh record in either form, read and validated.
    fn mesh(&mut self) -> Option<HalfEdgeMesh> {
        let mut positions = None;
        let mut faces: Option<(Vec<u32>, Vec<u32>)> = None;
        let mut records: Option<Vec<(u32, u32, u32, i64)>> = None;
        let mut vertex_halfedge: Option<Vec<i64>> = None;
        let mut face_halfedge = None;
        let mut d = PolygonData::default();
        self.expect(b'(')?;
        loop {
            if self.eat(b')') {
                break;
            }
            let name = self.ident()?;
            self.expect(b':')?;
            match name {
                "positions" if positions.is_none() => {
                    let mut p = Vec::new();
                    self.list(|c| {
                        c.expect(b'(')?;
                        let x = c.f64()?;
                        c.expect(b',')?;
                        let y = c.f64()?;
                        c.expect(b',')?;
                        let z = c.f64()?;
                        c.eat(b',');
                        c.expect(b')')?;
                        p.push(DVec3::new(x, y, z));
                        Some(())
                    })?;
                    positions = Some(p);
                }
                "faces" if faces.is_none() => {
                    let mut starts = vec![0u32];
                    let mut corners = Vec::new();
                    self.list(|c| {
                        c.list(|c| {
                            corners.push(c.u32()?);
                            Some(())
                        })?;
                        starts.push(u32::try_from(corners.len()).ok()?);
                        Some(())
                    })?;
                    faces = Some((starts, corners));
                }
                "corner_halfedges" => {
                    let mut v = Vec::new();
                    self.list(|c| {
                        let [a, b] = c.tuple(|c, _| c.u32())?;
                        v.push((a, b));
                        Some(())
                    })?;
                    d.corner_halfedges = v;
                }
                "vertex_halfedges" => {
                    let mut v = Vec::new();
                    self.list(|c| {
                        let [a, b] = c.tuple(|c, k| if k == 0 { c.u32() } else { c.id() })?;
                        v.push((a, b));
                        Some(())
                    })?;
                    d.vertex_halfedges = v;
                }
                "dead_halfedges" => {
                    let mut v = Vec::new();
                    self.list(|c| {
                        v.push(c.tuple(|c, _| c.u32())?);
                        Some(())
                    })?;
                    d.dead_halfedges = v;
                }
                "dead_vertices" => d.dead_vertices = self.u32_list()?,
                "dead_edges" => d.dead_edges = self.u32_list()?,
                "dead_faces" => d.dead_faces = self.u32_list()?,
                "dead_face_halfedges" => d.dead_face_halfedges = self.u32_list()?,
                "face_halfedge" if face_halfedge.is_none() => {
                    face_halfedge = Some(self.u32_list()?);
                }
                "vertex_halfedge" if vertex_halfedge.is_none() => {
                    let mut v = Vec::new();
                    self.list(|c| {
                        let x = c.id()?;
                        v.push(if x == NONE { -1 } else { i64::from(x) });
                        Some(())
                    })?;
                    vertex_halfedge = Some(v);
                }
                "halfedges" if records.is_none() => {
                    let mut v = Vec::new();
                    self.list(|c| {
                        let [o, n, p, f] = c.tuple(|c, k| if k == 3 { c.id() } else { c.u32() })?;
                        v.push((o, n, p, if f == NONE { -1 } else { i64::from(f) }));
                        Some(())
                    })?;
                    records = Some(v);
                }
                // Rings, lone vertices, unknown or repeated fields: serde's.
                _ => return None,
            }
            if !self.eat(b',') {
                self.expect(b')')?;
                break;
            }
        }
        d.positions = positions?;
        match (faces, records, vertex_halfedge, face_halfedge) {
            (Some((face_start, corners)), None, None, None) => {
                d.face_start = face_start;
                d.corners = corners;
                HalfEdgeMesh::try_from(d).ok()
            }
            (None, Some(halfedges), Some(vertex_halfedge), Some(face_halfedge))
                if d.corner_halfedges.is_empty()
                    && d.vertex_halfedges.is_empty()
                    && d.dead_halfedges.is_empty()
                    && d.dead_face_halfedges.is_empty() =>
            {
                HalfEdgeMesh::try_from(MeshData {
                    positions: d.positions,
                    vertex_halfedge,
                    halfedges,
                    face_halfedge,
                    dead_vertices: d.dead_vertices,
                    dead_edges: d.dead_edges,
                    dead_faces: d.dead_faces,
                    face_rings: Vec::new(),
                    lone_vertex_faces: Vec::new(),
                })
                .ok()
            }
            _ => None,
        }
    }

    /// Skips one RON value of any kind (up to the `,` or closing bracket
    /// after it).
    fn skip_value(&mut self) -> Option<()> {
        let mut depth = 0usize;
        loop {
            self.ws();
            let b = self.peek()?;
            match b {
                b'(' | b'[' | b'{' => {
                    depth += 1;
                    self.i += 1;
                }
                b')' | b']' | b'}' => {
                    if depth == 0 {
                        return Some(());
                    }
                    depth -= 1;
                    self.i += 1;
                    if depth == 0 {
                        return Some(());
                    }
                }
                b',' if depth == 0 => return Some(()),
                b'"' => {
                    self.skip_string()?;
                    if depth == 0 {
                        return Some(());
                    }
                }
                b'\'' => {
                    self.i += 1;
                    if self.peek()? == b'\\' {
                        self.i += 1;
                    }
                    self.i += 1;
                    // A char is one code point: skip to its closing quote.
                    while self.peek()? != b'\'' {
                        self.i += 1;
                    }
                    self.i += 1;
                    if depth == 0 {
                        return Some(());
                    }
                }
                b'a'..=b'z' | b'A'..=b'Z' | b'_' | b'0'..=b'9' => {
                    let start = self.i;
                    while let Some(b'a'..=b'z' | b'A'..=b'Z' | b'0'..=b'9' | b'_') = self.peek() {
                        self.i += 1;
                    }
                    let word = &self.b[start..self.i];
                    if matches!(word, b"r" | b"br" | b"b")
                        && matches!(self.peek(), Some(b'"' | b'#'))
                    {
                        let mut hashes = 0;
                        while self.peek() == Some(b'#') {
                            hashes += 1;
                            self.i += 1;
                        }
                        if self.peek()? != b'"' {
                            return None;
                        }
                        if word == b"b" && hashes == 0 {
                            self.skip_string()?;
                        } else {
                            self.skip_raw_string(hashes)?;
                        }
                    }
                    if depth == 0 && !matches!(self.peek(), Some(b'(' | b'.' | b'-' | b'+')) {
                        self.ws();
                        if !matches!(self.peek(), Some(b'(' | b'[' | b'{')) {
                            return Some(());
                        }
                    }
                }
                _ => self.i += 1,
            }
        }
    }

    /// Skips `"…"` with backslash escapes.
    fn skip_string(&mut self) -> Option<()> {
        self.i += 1;
        loop {
            match self.peek()? {
                b'\\' => self.i += 2,
                b'"' => {
                    self.i += 1;
                    return Some(());
                }
                _ => self.i += 1,
            }
        }
    }

    /// Skips `"…"#…` of a raw string with `hashes` hashes.
    fn skip_raw_string(&mut self, hashes: usize) -> Option<()> {
        self.i += 1;
        loop {
            if self.peek()? == b'"' {
                self.i += 1;
                let mut n = 0;
                while n < hashes && self.peek() == Some(b'#') {
                    n += 1;
                    self.i += 1;
                }
                if n == hashes {
                    return Some(());
                }
            } else {
                self.i += 1;
            }
        }
    }
}
