//! OBJ free-form curves (`cstype`, `deg`, `curv`, `parm`, `end`) read
//! as NURBS curves, and the polylines left out of the text given to tobj.

use super::obj::ObjError;
use glam::DVec3;

/// A free-form curve read from OBJ text, with the object or group it is in.
pub(super) struct ObjCurve {
    pub(super) name: Option<String>,
    pub(super) curve: hedra_geom::NurbsCurve,
}

/// The free-form state between `cstype` and `end`.
#[derive(Default)]
struct FreeForm {
    rational: bool,
    /// `bspline`, `bezier`, or another type (read, then left out).
    kind: String,
    degree: Option<usize>,
    /// The `curv` line: its number, range and vertex references.
    curv: Option<(usize, f64, f64, Vec<i64>)>,
    knots: Option<Vec<f64>>,
    /// A `surf`, `curv2` or another record Hedra does not read.
    other: bool,
}

/// Reads the free-form curves of OBJ text: B-spline and Bézier curves
/// (rational or not) become NURBS curves; a record of another type is
/// counted. Lines ending in `\` continue on the next. Vertices number
/// over the whole file, negative numbers back from the line.
///
/// # Errors
/// [`ObjError::FreeFormCurve`] naming the `curv` line and what is wrong.
pub(super) fn obj_curves(text: &str) -> Result<(Vec<ObjCurve>, usize), ObjError> {
    let mut vertices: Vec<(DVec3, f64)> = Vec::new();
    let (mut object, mut group): (Option<String>, Option<String>) = (None, None);
    let mut state = FreeForm::default();
    let mut out = Vec::new();
    let mut skipped = 0usize;
    let mut joined = String::new();
    let mut first_line = 0usize;
    for (number, raw) in text.lines().enumerate() {
        if joined.is_empty() {
            first_line = number + 1;
        }
        if let Some(head) = raw.trim_end().strip_suffix('\\') {
            joined.push_str(head);
            joined.push(' ');
            continue;
        }
        joined.push_str(raw);
        let line = std::mem::take(&mut joined);
        let number = first_line;
        let mut words = line.split_whitespace();
        let bad = |reason: String| ObjError::FreeFormCurve {
            line: number,
            reason,
        };
        let numbers = |words: std::str::SplitWhitespace| -> Result<Vec<f64>, ObjError> {
            words
                .map(|w| {
                    w.parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| bad(format!("'{w}' is not a finite number")))
                })
                .collect()
        };
        match words.next() {
            Some("v") => {
                let v: Vec<f64> = words.filter_map(|w| w.parse().ok()).collect();
                if v.len() >= 3 {
                    let w = if v.len() == 4 { v[3] } else { 1.0 };
                    vertices.push((DVec3::new(v[0], v[1], v[2]), w));
                }
            }
            Some("o") => {
                object = Some(line.trim_start()[1..].trim().to_string()).filter(|n| !n.is_empty());
                group = None;
            }
            Some("g") => {
                group = Some(line.trim_start()[1..].trim().to_string()).filter(|n| !n.is_empty());
            }
            Some("cstype") => {
                let rest: Vec<&str> = words.collect();
                state = FreeForm {
                    rational: rest.first() == Some(&"rat"),
                    kind: rest.last().copied().unwrap_or("").to_string(),
                    ..FreeForm::default()
                };
            }
            Some("deg") => {
                let d = words.next().and_then(|w| w.parse::<usize>().ok());
                state.degree = Some(d.ok_or_else(|| bad("'deg' needs a whole number".into()))?);
            }
            Some("curv") => {
                let all: Vec<&str> = words.collect();
                if all.len() < 4 {
                    return Err(bad("'curv' needs a range and two or more vertices".into()));
                }
                let range = numbers(all[..2].join(" ").split_whitespace())?;
                let refs = all[2..]
                    .iter()
                    .map(|w| {
                        w.parse::<i64>()
                            .map_err(|_| bad(format!("'{w}' is not a vertex number")))
                    })
                    .collect::<Result<Vec<i64>, _>>()?;
                state.curv = Some((number, range[0], range[1], refs));
            }
            Some("parm") if words.next() == Some("u") => {
                state.knots = Some(numbers(words)?);
            }
            Some("surf" | "curv2") => state.other = true,
            Some("end") => {
                let done = std::mem::take(&mut state);
                let Some((line, u0, u1, refs)) = done.curv.clone() else {
                    if done.other {
                        skipped += 1;
                    }
                    continue;
                };
                if done.other || !matches!(done.kind.as_str(), "bspline" | "bezier") {
                    skipped += 1;
                    continue;
                }
                let curve = free_form_curve(&done, &vertices, u0, u1, &refs)
                    .map_err(|reason| ObjError::FreeFormCurve { line, reason })?;
                out.push(ObjCurve {
                    name: group.clone().or_else(|| object.clone()),
                    curve,
                });
            }
            _ => {}
        }
    }
    Ok((out, skipped))
}

/// The NURBS curve of one free-form record, trimmed to `[u0, u1]`.
fn free_form_curve(
    f: &FreeForm,
    vertices: &[(DVec3, f64)],
    u0: f64,
    u1: f64,
    refs: &[i64],
) -> Result<hedra_geom::NurbsCurve, String> {
    use hedra_geom::curves::Curve;
    let degree = f.degree.ok_or("no 'deg' before 'end'")?;
    // Checked here, before anything computes `degree + 1`.
    if degree == 0 || degree >= refs.len() {
        return Err(format!(
            "degree {degree} does not fit {} control points (degree 1 to {})",
            refs.len(),
            refs.len() - 1
        ));
    }
    let mut points = Vec::with_capacity(refs.len());
    let mut weights = Vec::with_capacity(refs.len());
    for &r in refs {
        let i = if r < 0 {
            vertices.len() as i64 + r
        } else {
            r - 1
        };
        let &(p, w) = usize::try_from(i)
            .ok()
            .and_then(|i| vertices.get(i))
            .ok_or_else(|| format!("vertex {r} does not exist ({} come before)", vertices.len()))?;
        points.push(p);
        weights.push(if f.rational { w } else { 1.0 });
    }
    let knots = match (f.kind.as_str(), &f.knots) {
        ("bspline", Some(k)) => k.clone(),
        ("bspline", None) => return Err("no 'parm u' knots".into()),
        // Bézier: segments of `degree` points sharing ends, breakpoints
        // from `parm u` (uniform when absent).
        _ => {
            if !(refs.len() - 1).is_multiple_of(degree) {
                return Err(format!(
                    "a degree {degree} Bézier curve needs {degree}k + 1 points, got {}",
                    refs.len()
                ));
            }
            let segments = (refs.len() - 1) / degree;
            let breaks = f
                .knots
                .clone()
                .unwrap_or_else(|| (0..=segments).map(|i| i as f64).collect());
            if breaks.len() != segments + 1 {
                return Err(format!(
                    "{segments} Bézier segment(s) need {} 'parm u' values, got {}",
                    segments + 1,
                    breaks.len()
                ));
            }
            let mut k = vec![breaks[0]; degree + 1];
            for &b in &breaks[1..segments] {
                k.extend(std::iter::repeat_n(b, degree));
            }
            k.extend(std::iter::repeat_n(breaks[segments], degree + 1));
            k
        }
    };
    let curve =
        hedra_geom::NurbsCurve::new(degree, knots, points, weights).map_err(|e| e.to_string())?;
    let (a, b) = curve.domain();
    if !(u0 >= a && u1 <= b && u0 < u1) {
        return Err(format!(
            "the range [{u0}, {u1}] is not inside the knots' domain [{a}, {b}]"
        ));
    }
    let mut curve = curve;
    if u1 < b {
        curve = curve.split(u1).map_err(|e| e.to_string())?.0;
    }
    if u0 > a {
        curve = curve.split(u0).map_err(|e| e.to_string())?.1;
    }
    Ok(curve)
}

/// OBJ text without what tobj would misread, line numbers kept: polylines
/// (`l`, which tobj returns as faces) and `usemtl` lines with no name (which
/// tobj refuses; Blender 2.61 writes them) become empty lines. Returns the
/// text and the number of polylines left out.
pub(super) fn without_polylines(text: &str) -> (String, usize) {
    let mut polylines = 0;
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let mut words = line.split_whitespace();
        let drop = match words.next() {
            Some("l") => {
                polylines += 1;
                true
            }
            Some("usemtl") => words.next().is_none(),
            _ => false,
        };
        if drop {
            if line.ends_with('\n') {
                out.push('\n');
            }
        } else {
            out.push_str(line);
        }
    }
    (out, polylines)
}
