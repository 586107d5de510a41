//! Exports are streamed into their file (issue 36, item 2: "peak memory at
//! most the output size plus the mesh"): OBJ, STL and the GLB of a
//! subdivided mesh are never held whole. Measured with a counting allocator
//! (this test binary's own), against the memory of the subdivided mesh
//! the export writes from.

use hedra_doc::export::{ExportOptions, ExportShape, export_file, export_to_path, prepare_export};
use hedra_doc::{Command, NodeTransform, Session};
use hedra_geom::Primitive;
use hedra_geom::subdivision::{Creases, Options, Refiner};
use std::alloc::{GlobalAlloc, Layout, System};
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the bytes held and their peak.
struct Counting;

static HELD: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let held = HELD.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(held, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        HELD.fetch_sub(layout.size(), Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The tests measure one at a time (the counters are global).
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// Bytes allocated by `f` above what was held when it started, at their peak.
fn peak_of<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let start = HELD.load(Ordering::Relaxed);
    PEAK.store(start, Ordering::Relaxed);
    let out = f();
    (out, PEAK.load(Ordering::Relaxed) - start)
}

fn grid(segments: u32) -> Session {
    let mut s = Session::new();
    s.execute(&Command::AddPrimitive {
        primitive: Primitive::Grid {
            x_segments: segments,
            z_segments: segments,
            size: 2.0,
        },
        name: Some("Grid".into()),
        parent: None,
        transform: NodeTransform::IDENTITY,
    })
    .unwrap();
    s
}

const SUBDIVIDED: ExportOptions = ExportOptions {
    shape: ExportShape::Subdivided(1),
    ascii_stl: false,
    curves: hedra_doc::export::CurveExport::Polylines,
    step: hedra_doc::step::StepOptions {
        units: hedra_doc::step::StepUnits::Millimetres,
        meshes: false,
        subdivision_as_nurbs: false,
    },
};

#[test]
fn a_subdivided_export_holds_the_mesh_and_not_the_file() {
    let _one = ONE_AT_A_TIME.lock().unwrap();
    let session = grid(200);
    let node = session.doc.nodes().next().unwrap();
    let hedra_doc::NodeContent::Mesh(content) = &node.content else {
        panic!("the grid is a mesh")
    };
    // What the export writes from: the cage subdivided once.
    let options = Options {
        scheme: hedra_geom::subdivision::Scheme::CatmullClark,
        ..Options::default()
    };
    let (_, mesh_peak) =
        peak_of(|| Refiner::subdivide(&content.mesh, &Creases::default(), options, 1).unwrap());
    let folder = tempfile::tempdir().unwrap();
    for ext in ["stl", "obj", "glb"] {
        let path = folder.path().join(format!("grid.{ext}"));
        let (notes, export_peak) = peak_of(|| export_to_path(&session.doc, &path, SUBDIVIDED));
        assert!(notes.unwrap().is_empty());
        let size = std::fs::metadata(&path).unwrap().len() as usize;
        // The file is what the in-memory export makes, byte for byte.
        let in_memory = export_file(&session.doc, &path, SUBDIVIDED).unwrap().bytes;
        assert!(
            in_memory == std::fs::read(&path).unwrap(),
            "{ext}: the streamed file differs"
        );
        let bound = mesh_peak + size / 4;
        assert!(
            export_peak <= bound,
            "{ext}: the export held {export_peak} bytes at its peak; the subdivided mesh takes {mesh_peak} and the file is {size} bytes (allowed {bound})"
        );
    }
}

/// An output that takes `room` bytes and then fails, as a full disk does.
struct FullAfter {
    room: usize,
    position: u64,
}

impl std::io::Write for FullAfter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if buf.len() > self.room {
            return Err(std::io::Error::other("no space left on device"));
        }
        self.room -= buf.len();
        self.position += buf.len() as u64;
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl std::io::Seek for FullAfter {
    fn seek(&mut self, to: std::io::SeekFrom) -> std::io::Result<u64> {
        if let std::io::SeekFrom::Start(p) = to {
            self.position = p;
        }
        Ok(self.position)
    }
}

#[test]
fn a_full_disk_in_the_middle_of_an_export_is_an_error() {
    let _one = ONE_AT_A_TIME.lock().unwrap();
    let session = grid(20);
    for ext in ["stl", "obj", "glb", "gltf", "usda"] {
        let name = format!("grid.{ext}");
        let prepared = prepare_export(&session.doc, Path::new(&name), SUBDIVIDED).unwrap();
        let mut full = FullAfter {
            room: 1000,
            position: 0,
        };
        let error = prepared.write_to(&mut full).unwrap_err();
        assert_eq!(error.to_string(), "no space left on device", "{ext}");
    }
}

#[test]
fn a_failed_export_keeps_the_file_that_was_there() {
    let _one = ONE_AT_A_TIME.lock().unwrap();
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("grid.stl");
    std::fs::write(&path, b"the user's old file").unwrap();
    // A level too high to make: the export fails before anything is written.
    let too_deep = ExportOptions {
        shape: ExportShape::Subdivided(40),
        ..SUBDIVIDED
    };
    let error = export_to_path(&grid(4).doc, &path, too_deep).unwrap_err();
    assert!(error.to_string().contains("node 'Grid'"), "{error}");
    assert_eq!(std::fs::read(&path).unwrap(), b"the user's old file");
    let leftovers: Vec<_> = std::fs::read_dir(folder.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "only the old file: {leftovers:?}");
}
