//! Structured grids: rectangles (optionally distorted) and annular sectors.

use super::super::builder::MeshBuilder;
use super::super::fasthash::FastMap;
use super::super::{CellKind, Mesh};
use crate::error::{Error, Result};

/// Structured grid of nx × ny cells of `kind` over a parametric square mapped by `map`
/// (s, t) ∈ [0,1]² → (x, y); `mid` places mid-side nodes from the parametric midpoint.
/// Edge groups Bottom (t=0), Right (s=1), Top (t=1), Left (s=0); corner point groups.
fn grid(
    nx: usize,
    ny: usize,
    kind: CellKind,
    map: &dyn Fn(f64, f64) -> [f64; 2],
    source: &str,
) -> Result<Mesh> {
    if nx == 0 || ny == 0 {
        return Err(Error::model(format!(
            "{source}: cell counts must be positive, got {nx} x {ny}"
        )));
    }
    if kind.dim() != 2 {
        return Err(Error::model(format!(
            "{source}: cell kind {kind} is not a 2D kind (Tri3, Tri6, Quad4, Quad8)"
        )));
    }
    let quadratic = kind.is_quadratic();
    let mut b = MeshBuilder::new(source);
    let mut corner = vec![vec![0usize; ny + 1]; nx + 1];
    for (i, col) in corner.iter_mut().enumerate() {
        for (j, slot) in col.iter_mut().enumerate() {
            *slot = b.add_node(map(i as f64 / nx as f64, j as f64 / ny as f64));
        }
    }
    // mid-side nodes keyed by the doubled parametric grid position
    let mut mids: FastMap<(usize, usize), usize> = FastMap::default();
    let mut mid = |b: &mut MeshBuilder, i2: usize, j2: usize| -> usize {
        *mids.entry((i2, j2)).or_insert_with(|| {
            b.add_node(map(
                i2 as f64 / (2 * nx) as f64,
                j2 as f64 / (2 * ny) as f64,
            ))
        })
    };
    let mut label = 1;
    for i in 0..nx {
        for j in 0..ny {
            let (n0, n1, n2, n3) = (
                corner[i][j],
                corner[i + 1][j],
                corner[i + 1][j + 1],
                corner[i][j + 1],
            );
            let cells: Vec<(CellKind, Vec<usize>)> = match kind {
                CellKind::Quad4 => vec![(kind, vec![n0, n1, n2, n3])],
                CellKind::Quad8 => {
                    let m = [
                        mid(&mut b, 2 * i + 1, 2 * j),
                        mid(&mut b, 2 * i + 2, 2 * j + 1),
                        mid(&mut b, 2 * i + 1, 2 * j + 2),
                        mid(&mut b, 2 * i, 2 * j + 1),
                    ];
                    vec![(kind, vec![n0, n1, n2, n3, m[0], m[1], m[2], m[3]])]
                }
                CellKind::Tri3 => vec![(kind, vec![n0, n1, n2]), (kind, vec![n0, n2, n3])],
                _ => {
                    let m01 = mid(&mut b, 2 * i + 1, 2 * j);
                    let m12 = mid(&mut b, 2 * i + 2, 2 * j + 1);
                    let m23 = mid(&mut b, 2 * i + 1, 2 * j + 2);
                    let m30 = mid(&mut b, 2 * i, 2 * j + 1);
                    let mc = mid(&mut b, 2 * i + 1, 2 * j + 1);
                    vec![
                        (kind, vec![n0, n1, n2, m01, m12, mc]),
                        (kind, vec![n0, n2, n3, mc, m23, m30]),
                    ]
                }
            };
            for (k, nodes) in cells {
                let c = b.add_cell(k, &nodes, label);
                label += 1;
                b.add_to_cell_group("Body", c);
            }
        }
    }
    let edge = if quadratic {
        CellKind::Seg3
    } else {
        CellKind::Seg2
    };
    let add_edge = |b: &mut MeshBuilder,
                    group: &str,
                    a: usize,
                    c: usize,
                    m: Option<usize>,
                    label: &mut u64| {
        let nodes: Vec<usize> = match m {
            Some(m) => vec![a, c, m],
            None => vec![a, c],
        };
        let cell = b.add_cell(edge, &nodes, *label);
        *label += 1;
        b.add_to_cell_group(group, cell);
    };
    for i in 0..nx {
        let m = quadratic.then(|| mid(&mut b, 2 * i + 1, 0));
        add_edge(
            &mut b,
            "Bottom",
            corner[i][0],
            corner[i + 1][0],
            m,
            &mut label,
        );
        let m = quadratic.then(|| mid(&mut b, 2 * i + 1, 2 * ny));
        add_edge(
            &mut b,
            "Top",
            corner[i + 1][ny],
            corner[i][ny],
            m,
            &mut label,
        );
    }
    for j in 0..ny {
        let m = quadratic.then(|| mid(&mut b, 2 * nx, 2 * j + 1));
        add_edge(
            &mut b,
            "Right",
            corner[nx][j],
            corner[nx][j + 1],
            m,
            &mut label,
        );
        let m = quadratic.then(|| mid(&mut b, 0, 2 * j + 1));
        add_edge(
            &mut b,
            "Left",
            corner[0][j + 1],
            corner[0][j],
            m,
            &mut label,
        );
    }
    for (name, n) in [
        ("BottomLeft", corner[0][0]),
        ("BottomRight", corner[nx][0]),
        ("TopRight", corner[nx][ny]),
        ("TopLeft", corner[0][ny]),
    ] {
        let c = b.add_cell(CellKind::Point1, &[n], label);
        label += 1;
        b.add_to_cell_group(name, c);
    }
    b.finish()
}

/// Deterministic pseudo-random number in [-1, 1] from two indices.
fn wiggle(i: u64, j: u64, salt: u64) -> f64 {
    let mut h = i.wrapping_mul(0x9E3779B97F4A7C15) ^ j.wrapping_mul(0xC2B2AE3D27D4EB4F) ^ salt;
    h ^= h >> 31;
    h = h.wrapping_mul(0xBF58476D1CE4E5B9);
    h ^= h >> 29;
    (h % 2_000_001) as f64 / 1_000_000.0 - 1.0
}

/// Rectangle [x0, x0 + width] × [y0, y0 + height] in nx × ny cells (Tri kinds: each
/// square split in two). `distortion` < 0.3 moves interior grid points pseudo-randomly by up
/// to that fraction of a cell (boundary points along their side only); cells stay straight-sided.
pub fn rectangle(
    origin: [f64; 2],
    width: f64,
    height: f64,
    nx: usize,
    ny: usize,
    kind: CellKind,
    distortion: f64,
) -> Result<Mesh> {
    if !(width > 0.0 && height > 0.0) {
        return Err(Error::model(format!(
            "rectangle: width and height must be positive, got {width} x {height}"
        )));
    }
    if !(0.0..0.3).contains(&distortion) {
        return Err(Error::model(format!(
            "rectangle: distortion must lie in [0, 0.3), got {distortion}"
        )));
    }
    let (hx, hy) = (1.0 / nx.max(1) as f64, 1.0 / ny.max(1) as f64);
    let map = |s: f64, t: f64| -> [f64; 2] {
        // Distort the corner grid only (mid-side points interpolate their corners).
        let (fi, fj) = (s / hx, t / hy);
        let on_grid = |f: f64| (f - f.round()).abs() < 1e-9;
        let (mut ss, mut tt) = (s, t);
        if distortion > 0.0 {
            let corner = |fi: f64, fj: f64| -> [f64; 2] {
                let (i, j) = (fi.round() as u64, fj.round() as u64);
                let mut c = [fi * hx, fj * hy];
                let interior_s = i > 0 && i < nx as u64;
                let interior_t = j > 0 && j < ny as u64;
                if interior_s {
                    c[0] += distortion * hx * wiggle(i, j, 1);
                }
                if interior_t {
                    c[1] += distortion * hy * wiggle(i, j, 2);
                }
                c
            };
            if on_grid(fi) && on_grid(fj) {
                [ss, tt] = corner(fi, fj);
            } else {
                // a mid-side point (or the Tri6 diagonal's, (i0,j0)-(i1,j1)) sits halfway
                // between its two grid corners, keeping the sides straight
                let span = |f: f64| {
                    if on_grid(f) {
                        (f.round(), f.round())
                    } else {
                        (f.floor(), f.ceil())
                    }
                };
                let ((i0, i1), (j0, j1)) = (span(fi), span(fj));
                let (p, q) = (corner(i0, j0), corner(i1, j1));
                [ss, tt] = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
            }
        }
        [origin[0] + width * ss, origin[1] + height * tt]
    };
    grid(nx, ny, kind, &map, "rectangle")
}

/// Annular sector r ∈ [r_in, r_out], θ ∈ [0, angle] degrees, n_r × n_theta cells; every
/// node (mid-side ones too) is placed in polar coordinates, so curved sides follow the
/// circles. Edge groups Inner, Outer, Start (θ = 0), End (θ = angle). With angle = 360 the
/// ring is whole: the seam's nodes are merged, and the groups are Body, Inner and Outer
/// (closed curves).
pub fn ring(
    r_in: f64,
    r_out: f64,
    n_r: usize,
    n_theta: usize,
    angle_deg: f64,
    kind: CellKind,
) -> Result<Mesh> {
    if !(r_in > 0.0 && r_out > r_in) {
        return Err(Error::model(format!(
            "ring: need 0 < r_in < r_out, got r_in = {r_in}, r_out = {r_out}"
        )));
    }
    if !(angle_deg > 0.0 && angle_deg <= 360.0) {
        return Err(Error::model(format!(
            "ring: angle must lie in (0, 360] degrees, got {angle_deg}"
        )));
    }
    let a = angle_deg.to_radians();
    let map = |s: f64, t: f64| -> [f64; 2] {
        let r = r_in + (r_out - r_in) * s;
        let th = a * t;
        [r * th.cos(), r * th.sin()]
    };
    let m = grid(n_r, n_theta, kind, &map, "ring")?;
    if angle_deg == 360.0 {
        return whole_ring(&m, r_out);
    }
    // grid names: s = radius, t = angle → Left = inner, Right = outer, Bottom = start, Top = end
    let mut b = MeshBuilder::new("ring");
    b.append(&m, |g| {
        match g {
            "Left" => "Inner",
            "Right" => "Outer",
            "Bottom" => "Start",
            "Top" => "End",
            other => other,
        }
        .to_string()
    });
    b.finish()
}

/// The grid of a ring swept over 360°, its seam closed: the nodes at θ = 360° are those
/// at θ = 0 (y = 0, x > 0). Groups: Body, Inner, Outer.
fn whole_ring(m: &Mesh, r_out: f64) -> Result<Mesh> {
    let tol = 1e-9 * r_out;
    let mut seam: Vec<(f64, usize)> = vec![];
    let mut same: Vec<usize> = (0..m.num_nodes()).collect();
    for (i, x) in m.coords.iter().enumerate() {
        if x[1].abs() <= tol && x[0] > 0.0 {
            match seam.iter().find(|s| (s.0 - x[0]).abs() <= tol) {
                Some(&(_, j)) => same[i] = j,
                None => seam.push((x[0], i)),
            }
        }
    }
    let mut b = MeshBuilder::new("ring");
    let mut index = vec![usize::MAX; m.num_nodes()];
    for i in 0..m.num_nodes() {
        if same[i] == i {
            index[i] = b.add_node(m.coords[i]);
        }
    }
    let mut kept = vec![usize::MAX; m.num_cells()];
    for c in 0..m.num_cells() {
        let nodes: Vec<usize> = m.cell_nodes(c).iter().map(|&n| index[same[n]]).collect();
        // the edges along the seam are inside the whole ring now
        let on_seam = m.kind(c).dim() == 1 && nodes.iter().all(|&n| b.coords()[n][1] == 0.0);
        if m.kind(c).dim() != 0 && !on_seam {
            kept[c] = b.add_cell(m.kind(c), &nodes, c as u64 + 1);
        }
    }
    for (from, to) in [("Body", "Body"), ("Left", "Inner"), ("Right", "Outer")] {
        for &c in m.cell_group(from)? {
            if kept[c] != usize::MAX {
                b.add_to_cell_group(to, kept[c]);
            }
        }
    }
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::super::area;
    use super::*;

    #[test]
    fn rectangle_areas_and_groups() {
        for kind in [
            CellKind::Tri3,
            CellKind::Tri6,
            CellKind::Quad4,
            CellKind::Quad8,
        ] {
            let m = rectangle([1.0, 2.0], 3.0, 2.0, 6, 4, kind, 0.2).unwrap();
            assert!((area(&m) - 6.0).abs() < 1e-12, "{kind}");
            assert_eq!(m.cell_group("Bottom").unwrap().len(), 6);
            assert_eq!(m.cell_group("Left").unwrap().len(), 4);
            assert_eq!(
                m.node_group("Bottom").unwrap().len(),
                if kind.is_quadratic() { 13 } else { 7 }
            );
            assert_eq!(m.coords[m.single_node("TopRight").unwrap()], [4.0, 4.0]);
            assert_eq!(m.reoriented, 0);
        }
    }

    #[test]
    fn ring_areas_and_groups() {
        let exact = std::f64::consts::PI / 4.0 * (4.0 - 1.0);
        let lin = ring(1.0, 2.0, 4, 16, 90.0, CellKind::Quad4).unwrap();
        assert!((area(&lin) - exact).abs() < 2e-2 * exact);
        for kind in [CellKind::Quad8, CellKind::Tri6] {
            let quad = ring(1.0, 2.0, 4, 16, 90.0, kind).unwrap();
            assert!(
                (area(&quad) - exact).abs() < 1e-5 * exact,
                "{kind}: {}",
                area(&quad)
            );
            for n in quad.node_group("Inner").unwrap() {
                let x = quad.coords[n];
                assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-14);
            }
        }
        assert_eq!(lin.cell_group("Outer").unwrap().len(), 16);
        assert_eq!(lin.cell_group("Start").unwrap().len(), 4);
    }

    #[test]
    fn whole_ring_is_closed() {
        let exact = std::f64::consts::PI * (4.0 - 1.0);
        for kind in [CellKind::Quad4, CellKind::Quad8, CellKind::Tri6] {
            let m = ring(1.0, 2.0, 2, 24, 360.0, kind).unwrap();
            let tol = if kind == CellKind::Quad4 { 2e-2 } else { 1e-5 };
            assert!(
                (area(&m) - exact).abs() < tol * exact,
                "{kind}: {}",
                area(&m)
            );
            // closed circles: every node of a circle is on two of its edges
            for g in ["Inner", "Outer"] {
                let mut count = vec![0; m.num_nodes()];
                for &c in m.cell_group(g).unwrap() {
                    let nodes = m.cell_nodes(c);
                    count[nodes[0]] += 1;
                    count[nodes[1]] += 1;
                }
                assert!(count.iter().all(|&k| k == 0 || k == 2), "{kind} {g}");
                assert_eq!(m.cell_group(g).unwrap().len(), 24);
            }
            let names: Vec<String> = m.cell_groups.keys().cloned().collect();
            assert_eq!(names, ["Body", "Inner", "Outer"]);
            let per_ring = if kind.is_quadratic() { 48 } else { 24 };
            let expected = match kind {
                CellKind::Quad4 => 3 * 24,
                CellKind::Quad8 => 3 * per_ring + 2 * 24,
                _ => 3 * per_ring + 2 * 48,
            };
            assert_eq!(m.num_nodes(), expected, "{kind}");
        }
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(rectangle([0.0, 0.0], -1.0, 1.0, 2, 2, CellKind::Quad4, 0.0).is_err());
        assert!(rectangle([0.0, 0.0], 1.0, 1.0, 0, 2, CellKind::Quad4, 0.0).is_err());
        assert!(rectangle([0.0, 0.0], 1.0, 1.0, 2, 2, CellKind::Seg2, 0.0).is_err());
        assert!(ring(2.0, 1.0, 2, 2, 90.0, CellKind::Quad4).is_err());
    }
}
