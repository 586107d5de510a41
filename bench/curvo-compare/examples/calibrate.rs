//! Finds which curvo tessellation settings give about the same chord error as
//! Hedra's `tessellate_nurbs(&s, 0.001)`: curvo has no distance tolerance, only
//! a normal tolerance (and edge lengths), so the setting is chosen by
//! measurement. Prints one line per setting.

use curvo::prelude::*;
use curvo_compare::*;
use hedra_geom::surfaces::tessellate::{cells_for_tolerance, tessellate_nurbs};
use std::time::Instant;

fn main() {
    let d = surface_data();
    let (h, c) = (hedra_surface(&d), curvo_surface(&d));
    let t0 = Instant::now();
    let m = tessellate_nurbs(&h, 0.001);
    let dt = t0.elapsed();
    let (p, uv, tri) = hedra_mesh(&m);
    let (emax, emean) = chord_error(&h, &p, &uv, &tri);
    println!(
        "hedra tol 0.001: cells {:?}, {} verts, {} tris, chord err max {emax:.2e} mean {emean:.2e}, {:.1} ms",
        cells_for_tolerance(&h, 0.001),
        p.len(),
        tri.len(),
        dt.as_secs_f64() * 1e3
    );
    if std::env::var("HEDRA_ONLY").is_ok() {
        return;
    }
    let depths: Vec<usize> = std::env::var("DEPTHS")
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![8, 10]);
    let tols: Vec<f64> = std::env::var("TOLS")
        .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
        .unwrap_or(vec![2.5e-2, 1e-2, 5e-3, 2e-3]);
    for &depth in &depths {
        for &nt in &tols {
            for &grid in &[false, true] {
                let opts = AdaptiveTessellationOptions::<f64>::default()
                    .with_norm_tolerance(nt)
                    .with_max_depth(depth)
                    .with_grid(grid);
                let t0 = Instant::now();
                let t = c.tessellate(Some(opts));
                let dt = t0.elapsed();
                let (p, uv, tri) = curvo_mesh(&t);
                let (emax, emean) = chord_error(&h, &p, &uv, &tri);
                println!(
                    "curvo norm_tol {nt:.0e} depth {depth} grid {grid}: {} verts, {} tris, chord err max {emax:.2e} mean {emean:.2e}, {:.1} ms",
                    p.len(),
                    tri.len(),
                    dt.as_secs_f64() * 1e3
                );
            }
        }
    }
}
