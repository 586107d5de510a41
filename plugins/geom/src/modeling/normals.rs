//! Face orientation: flipping every face and making closed shells face
//! outwards (the relinking itself is in [`crate::mesh`], which owns the
//! half-edge records).

use crate::mesh::HalfEdgeMesh;

/// Reverses the orientation of every face (flip normals). Connectivity is
/// relinked half-edge by half-edge: origin becomes the old target, next and
/// prev swap. ΔV = ΔE = ΔF = 0; applying it twice restores the mesh.
pub fn flip_normals(mesh: &mut HalfEdgeMesh) {
    mesh.reverse_orientation();
}

/// Makes closed shells face outwards: a shell with negative volume is
/// flipped. Open shells are left as they are.
pub fn recalculate_normals_outward(mesh: &mut HalfEdgeMesh) -> bool {
    if mesh.boundary_loops().is_empty() && mesh.volume() < 0.0 {
        mesh.reverse_orientation();
        true
    } else {
        false
    }
}
