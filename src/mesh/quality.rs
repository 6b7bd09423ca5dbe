//! Mesh quality figures shown by `tribo mesh info`.

use super::Mesh;

#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Quality {
    /// Smallest interior corner angle over all 2D cells, degrees.
    pub min_angle_deg: f64,
    /// Largest ratio of longest to shortest corner-to-corner edge over all 2D cells.
    pub max_aspect_ratio: f64,
}

/// Axis-aligned bounding box of the nodes: ([xmin, ymin], [xmax, ymax]).
pub fn bounding_box(mesh: &Mesh) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for x in &mesh.coords {
        for d in 0..2 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    (lo, hi)
}

pub fn quality(mesh: &Mesh) -> Option<Quality> {
    let mut min_angle = f64::INFINITY;
    let mut max_ar: f64 = 0.0;
    for c in mesh.cells_of_dim(2) {
        let kind = mesh.kind(c);
        let nc = kind.num_corners();
        let nodes = mesh.cell_nodes(c);
        let mut p = [[0.0; 2]; 4];
        for (slot, &n) in p.iter_mut().zip(&nodes[..nc]) {
            *slot = mesh.coords[n];
        }
        // side k runs from corner k to k + 1; one length per side
        let mut len = [0.0; 4];
        for k in 0..nc {
            let (a, b) = (p[k], p[(k + 1) % nc]);
            len[k] = (b[0] - a[0]).hypot(b[1] - a[1]);
        }
        let (mut lmin, mut lmax) = (f64::INFINITY, 0.0f64);
        for i in 0..nc {
            let a = p[i];
            let b = p[(i + 1) % nc];
            let prev = p[(i + nc - 1) % nc];
            let e1 = [b[0] - a[0], b[1] - a[1]];
            let e2 = [prev[0] - a[0], prev[1] - a[1]];
            let (l1, l2) = (len[i], len[(i + nc - 1) % nc]);
            lmin = lmin.min(l1);
            lmax = lmax.max(l1);
            let cos = ((e1[0] * e2[0] + e1[1] * e2[1]) / (l1 * l2)).clamp(-1.0, 1.0);
            min_angle = min_angle.min(cos.acos().to_degrees());
        }
        max_ar = max_ar.max(lmax / lmin);
    }
    min_angle.is_finite().then_some(Quality {
        min_angle_deg: min_angle,
        max_aspect_ratio: max_ar,
    })
}
