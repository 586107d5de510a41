//! Import and export speed of a 1M-triangle mesh (issue 14), one phase per
//! run so that `/usr/bin/time -v` gives each phase's peak memory:
//!
//! ```text
//! cargo run --release -p hedra_doc --example interchange_speed -- DIR PHASE
//! ```
//!
//! PHASE: `make` writes DIR/grid.obj (a 708 × 708 grid of quads, each split
//! into two triangles: 1,002,528 triangles); `obj`, `stl`, `glb` import that
//! format from DIR (`make-exports` writes grid.stl and grid.glb first) and
//! export it again; `scene` saves and loads the imported OBJ as a scene
//! file, `scene-attrs` the same grid with a UV and a normal on every corner
//! (`make-attrs` writes it). Times are printed in seconds.

use hedra_doc::export::{ExportOptions, export_bytes};
use hedra_doc::import::import_file;
use hedra_doc::{Session, file};
use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

const N: usize = 708;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (dir, phase) = (Path::new(&args[1]), args[2].as_str());
    let time = |what: &str, f: &mut dyn FnMut()| {
        let t = Instant::now();
        f();
        println!("{what}: {:.3} s", t.elapsed().as_secs_f64());
    };
    match phase {
        "make" => {
            let mut text = String::new();
            for j in 0..=N {
                for i in 0..=N {
                    let _ = writeln!(text, "v {} 0 {}", i as f64 / N as f64, j as f64 / N as f64);
                }
            }
            let id = |i: usize, j: usize| j * (N + 1) + i + 1;
            for j in 0..N {
                for i in 0..N {
                    let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                    let _ = writeln!(text, "f {a} {d} {c}\nf {a} {c} {b}");
                }
            }
            std::fs::write(dir.join("grid.obj"), text).unwrap();
        }
        "make-exports" => {
            let mut s = Session::new();
            s.import(&import_file(&dir.join("grid.obj")).unwrap(), "Import");
            for ext in ["stl", "glb"] {
                let bytes = export_bytes(
                    &s.doc,
                    &dir.join(format!("x.{ext}")),
                    ExportOptions::default(),
                )
                .unwrap();
                std::fs::write(dir.join(format!("grid.{ext}")), bytes).unwrap();
            }
        }
        "obj" | "stl" | "glb" => {
            let path = dir.join(format!("grid.{phase}"));
            let mut meshes = Vec::new();
            time(&format!("import {phase}"), &mut || {
                meshes = import_file(&path).unwrap()
            });
            let faces: usize = meshes
                .iter()
                .filter_map(|m| m.mesh.as_ref())
                .map(|m| m.face_count())
                .sum();
            println!("faces: {faces}");
            let mut s = Session::new();
            s.import(&meshes, "Import");
            drop(meshes);
            let out = dir.join(format!("out.{phase}"));
            time(&format!("export {phase}"), &mut || {
                let bytes = export_bytes(&s.doc, &out, ExportOptions::default()).unwrap();
                std::fs::write(&out, bytes).unwrap();
            });
        }
        "make-attrs" => {
            // The grid with a UV and a normal on every corner.
            let mut text = String::new();
            for j in 0..=N {
                for i in 0..=N {
                    let (u, v) = (i as f64 / N as f64, j as f64 / N as f64);
                    let _ = writeln!(text, "v {u} 0 {v}\nvt {u} {v}");
                }
            }
            text.push_str("vn 0 1 0\n");
            let id = |i: usize, j: usize| j * (N + 1) + i + 1;
            let c = |k: usize| format!("{k}/{k}/1");
            for j in 0..N {
                for i in 0..N {
                    let (a, b, cc, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                    let _ = writeln!(
                        text,
                        "f {} {} {}\nf {} {} {}",
                        c(a),
                        c(d),
                        c(cc),
                        c(a),
                        c(cc),
                        c(b)
                    );
                }
            }
            std::fs::write(dir.join("attrs.obj"), text).unwrap();
        }
        "scene" | "scene-attrs" => {
            let source = if phase == "scene" {
                "grid.obj"
            } else {
                "attrs.obj"
            };
            let mut s = Session::new();
            s.import(&import_file(&dir.join(source)).unwrap(), "Import");
            let path = dir.join("grid.hedra.ron");
            time("save scene", &mut || file::save(&mut s, &path).unwrap());
            println!(
                "scene file: {} bytes",
                std::fs::metadata(&path).unwrap().len()
            );
            time("load scene", &mut || {
                file::load(&path).unwrap();
            });
        }
        other => panic!("unknown phase {other}"),
    }
}
