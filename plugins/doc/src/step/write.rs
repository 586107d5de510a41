//! The STEP text writer: instance numbering, Part 21 values, the header,
//! the AP214 product structure and unit context, B-spline curves and
//! surfaces (polynomial as simple instances, rational as complex ones).

use super::StepUnits;
use super::p21::encode_string;
use glam::DVec3;
use hedra_geom::{NurbsCurve, NurbsSurface};
use std::fmt::Write;

/// Writes the data section of a STEP file, numbering instances from 1.
pub struct StepWriter {
    data: String,
    next: u64,
}

impl Default for StepWriter {
    fn default() -> Self {
        Self::new()
    }
}

/// A real as Part 21 writes it: always with a decimal point, exponent in
/// upper case, the shortest digits that read back to the same `f64`.
pub fn real(x: f64) -> String {
    let x = if x == 0.0 { 0.0 } else { x };
    let s = format!("{x:?}");
    match s.split_once('e') {
        Some((m, e)) => {
            let m = if m.contains('.') {
                m.to_string()
            } else {
                format!("{m}.")
            };
            format!("{m}E{e}")
        }
        None => s,
    }
}

/// A string value, quoted and escaped.
pub fn string(s: &str) -> String {
    format!("'{}'", encode_string(s))
}

/// `(a,b,c)` of already written values.
pub fn list<I: IntoIterator<Item = String>>(items: I) -> String {
    let v: Vec<String> = items.into_iter().collect();
    format!("({})", v.join(","))
}

/// `#n`.
pub fn r(id: u64) -> String {
    format!("#{id}")
}

/// `.T.` or `.F.`.
pub fn logical(b: bool) -> &'static str {
    if b { ".T." } else { ".F." }
}

/// Distinct knots and their multiplicities (exactly equal values merge).
pub fn knot_runs(knots: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let (mut values, mut counts): (Vec<f64>, Vec<usize>) = (Vec::new(), Vec::new());
    for &k in knots {
        if values.last() == Some(&k) {
            *counts.last_mut().expect("a value has a count") += 1;
        } else {
            values.push(k);
            counts.push(1);
        }
    }
    (values, counts)
}

impl StepWriter {
    /// An empty data section.
    pub fn new() -> Self {
        StepWriter {
            data: String::new(),
            next: 1,
        }
    }

    /// Writes `#n = body;` and returns n.
    pub fn add(&mut self, body: &str) -> u64 {
        let id = self.next;
        self.next += 1;
        let _ = writeln!(self.data, "#{id} = {body};");
        id
    }

    /// A `CARTESIAN_POINT`.
    pub fn point(&mut self, p: DVec3) -> u64 {
        self.add(&format!(
            "CARTESIAN_POINT('',({},{},{}))",
            real(p.x),
            real(p.y),
            real(p.z)
        ))
    }

    /// A `DIRECTION`.
    pub fn direction(&mut self, d: DVec3) -> u64 {
        self.add(&format!(
            "DIRECTION('',({},{},{}))",
            real(d.x),
            real(d.y),
            real(d.z)
        ))
    }

    /// An `AXIS2_PLACEMENT_3D` at `origin` with axis `z` and reference
    /// direction `x`.
    pub fn placement(&mut self, origin: DVec3, z: DVec3, x: DVec3) -> u64 {
        let o = self.point(origin);
        let z = self.direction(z);
        let x = self.direction(x);
        self.add(&format!("AXIS2_PLACEMENT_3D('',#{o},#{z},#{x})"))
    }

    /// A B-spline curve: `B_SPLINE_CURVE_WITH_KNOTS`, or the complex
    /// instance with `RATIONAL_B_SPLINE_CURVE` when a weight is not 1.
    pub fn bspline_curve(&mut self, name: &str, c: &NurbsCurve) -> u64 {
        let points: Vec<String> = c.points().iter().map(|&p| r(self.point(p))).collect();
        let (knots, mults) = knot_runs(c.knots());
        let mults = list(mults.iter().map(|m| m.to_string()));
        let knots = list(knots.iter().map(|&k| real(k)));
        let points = list(points);
        let degree = c.degree();
        if c.is_polynomial() {
            self.add(&format!(
                "B_SPLINE_CURVE_WITH_KNOTS({},{degree},{points},.UNSPECIFIED.,.F.,.F.,{mults},{knots},.UNSPECIFIED.)",
                string(name)
            ))
        } else {
            let weights = list(c.weights().iter().map(|&w| real(w)));
            self.add(&format!(
                "( BOUNDED_CURVE() B_SPLINE_CURVE({degree},{points},.UNSPECIFIED.,.F.,.F.) B_SPLINE_CURVE_WITH_KNOTS({mults},{knots},.UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE({weights}) REPRESENTATION_ITEM({}) )",
                string(name)
            ))
        }
    }

    /// A B-spline surface: `B_SPLINE_SURFACE_WITH_KNOTS`, or the complex
    /// instance with `RATIONAL_B_SPLINE_SURFACE` when a weight is not 1.
    /// Control points row by row in u (`points[i * nv + j]` is row i,
    /// column j), as STEP's `control_points_list[i][j]`.
    pub fn bspline_surface(&mut self, name: &str, s: &NurbsSurface) -> u64 {
        let (nu, nv) = s.size();
        let ids: Vec<u64> = s.points().iter().map(|&p| self.point(p)).collect();
        let rows = list((0..nu).map(|i| list((0..nv).map(|j| r(ids[i * nv + j])))));
        let (ku, kv) = s.knots();
        let (ku, mu) = knot_runs(ku);
        let (kv, mv) = knot_runs(kv);
        let knots = format!(
            "{},{},{},{}",
            list(mu.iter().map(|m| m.to_string())),
            list(mv.iter().map(|m| m.to_string())),
            list(ku.iter().map(|&k| real(k))),
            list(kv.iter().map(|&k| real(k)))
        );
        let (du, dv) = s.degrees();
        if s.weights().iter().all(|&w| w == 1.0) {
            self.add(&format!(
                "B_SPLINE_SURFACE_WITH_KNOTS({},{du},{dv},{rows},.UNSPECIFIED.,.F.,.F.,.F.,{knots},.UNSPECIFIED.)",
                string(name)
            ))
        } else {
            let w = s.weights();
            let weights = list((0..nu).map(|i| list((0..nv).map(|j| real(w[i * nv + j])))));
            self.add(&format!(
                "( BOUNDED_SURFACE() B_SPLINE_SURFACE({du},{dv},{rows},.UNSPECIFIED.,.F.,.F.,.F.) B_SPLINE_SURFACE_WITH_KNOTS({knots},.UNSPECIFIED.) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE({weights}) REPRESENTATION_ITEM({}) SURFACE() )",
                string(name)
            ))
        }
    }

    /// The geometric context: 3D, the length unit, radians, steradians,
    /// and the distance uncertainty (in the file's length unit).
    pub fn context(&mut self, units: StepUnits, uncertainty: f64) -> u64 {
        let length = match units {
            StepUnits::Metres => "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) )",
            StepUnits::Millimetres => "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )",
        };
        let length = self.add(length);
        let angle = self.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )");
        let solid = self.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )");
        let accuracy = self.add(&format!(
            "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{length},'distance_accuracy_value','confusion accuracy')",
            real(uncertainty)
        ));
        self.add(&format!(
            "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{accuracy})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY') )"
        ))
    }

    /// The AP214 product structure around the shape representation
    /// `representation`: one part named `name`.
    pub fn product(&mut self, name: &str, representation: u64) {
        let app =
            self.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
        self.add(&format!(
            "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
        ));
        let pc = self.add(&format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
        let n = string(name);
        let product = self.add(&format!("PRODUCT({n},{n},'',(#{pc}))"));
        self.add(&format!(
            "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
        ));
        let formation = self.add(&format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
        let pdc = self.add(&format!(
            "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
        ));
        let pd = self.add(&format!(
            "PRODUCT_DEFINITION('design','',#{formation},#{pdc})"
        ));
        let pds = self.add(&format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
        self.add(&format!(
            "SHAPE_DEFINITION_REPRESENTATION(#{pds},#{representation})"
        ));
    }

    /// The whole file: header (description, file name, AP214 schema) and
    /// the data section.
    pub fn finish(self, file_name: &str, description: &str) -> Vec<u8> {
        let mut out = String::with_capacity(self.data.len() + 1024);
        out.push_str("ISO-10303-21;\nHEADER;\n");
        let _ = writeln!(out, "FILE_DESCRIPTION(({}),'2;1');", string(description));
        let _ = writeln!(
            out,
            "FILE_NAME({},'',(''),(''),{},'Hedra','');",
            string(file_name),
            string(&format!("Hedra {}", env!("CARGO_PKG_VERSION")))
        );
        out.push_str(
            "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n",
        );
        out.push_str(&self.data);
        out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
        out.into_bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_have_a_point_and_read_back_exactly() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -2.5,
            1e-7,
            1.234e300,
            0.1 + 0.2,
            f64::MIN_POSITIVE,
        ] {
            let s = real(x);
            assert!(s.contains('.'), "{s}");
            let text =
                format!("ISO-10303-21;HEADER;ENDSEC;DATA;#1=A({s});ENDSEC;END-ISO-10303-21;");
            let ex = super::super::p21::parse(text.as_bytes()).unwrap();
            assert_eq!(
                ex.instances[&1].records[0].params[0],
                super::super::p21::Param::Real(if x == 0.0 { 0.0 } else { x }),
                "{s}"
            );
        }
    }

    #[test]
    fn knots_become_values_and_multiplicities() {
        assert_eq!(
            knot_runs(&[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]),
            (vec![0.0, 0.5, 1.0], vec![3, 1, 3])
        );
    }
}
