//! OpenUSD export and import (issue 32), checked by Pixar's usd-core.

use hedra_doc::export::ExportShape;
use std::path::Path;

#[test]
fn smoke() {
    for s in ["cup", "jar", "csg", "chair", "shapes", "table", "g1-join"] {
        let p = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("../../assets/samples/{s}.hedra.ron"));
        let loaded = hedra_doc::file::load(&p).unwrap();
        let doc = &loaded.session.doc;
        let out = Path::new("/tmp/usdt").join(format!("{s}.usda"));
        let (bytes, notes) = hedra_doc::usd::to_usd(doc, &out, ExportShape::Evaluated).unwrap();
        std::fs::write(&out, bytes).unwrap();
        eprintln!("{s}: {notes:?}");
        let back = hedra_doc::import::import_file(&out);
        match back {
            Ok(m) => eprintln!("{s}: {} nodes; {:?}", m.len(), m[0].not_imported),
            Err(e) => eprintln!("{s}: ERROR {e}"),
        }
    }
}
