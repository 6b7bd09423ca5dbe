//! Meshes the generators do not make (full rings, a plate with a hole, a half disc), built
//! from mapped quadrilateral patches whose coincident nodes are merged by position.

use std::collections::HashMap;
use tribo::mesh::{CellKind, Mesh, MeshBuilder};

pub struct Patches {
    b: MeshBuilder,
    at: HashMap<(i64, i64), usize>,
    label: u64,
    kind: CellKind,
}

impl Patches {
    /// `kind`: Quad4 or Quad8.
    pub fn new(kind: CellKind) -> Self {
        Patches {
            b: MeshBuilder::new("test patches"),
            at: HashMap::new(),
            label: 1,
            kind,
        }
    }

    /// The node at x, shared with any earlier node within 1e-9.
    fn node(&mut self, x: [f64; 2]) -> usize {
        let key = ((x[0] * 1e9).round() as i64, (x[1] * 1e9).round() as i64);
        if let Some(&n) = self.at.get(&key) {
            return n;
        }
        let n = self.b.add_node(x);
        self.at.insert(key, n);
        n
    }

    /// ns × nt cells over (s, t) ∈ [0, 1]² mapped by `map`, in cell group `body`; the
    /// edges s = 0 go in `inner` and s = 1 in `outer` when named.
    pub fn patch(
        &mut self,
        ns: usize,
        nt: usize,
        map: &dyn Fn(f64, f64) -> [f64; 2],
        body: &str,
        inner: Option<&str>,
        outer: Option<&str>,
    ) {
        let quadratic = self.kind == CellKind::Quad8;
        let (fs, ft) = ((2 * ns) as f64, (2 * nt) as f64);
        // node at doubled parametric indices
        let at =
            |p: &mut Patches, i2: usize, j2: usize| p.node(map(i2 as f64 / fs, j2 as f64 / ft));
        let edge = if quadratic {
            CellKind::Seg3
        } else {
            CellKind::Seg2
        };
        for i in 0..ns {
            for j in 0..nt {
                let (i2, j2) = (2 * i, 2 * j);
                let mut nodes = vec![
                    at(self, i2, j2),
                    at(self, i2 + 2, j2),
                    at(self, i2 + 2, j2 + 2),
                    at(self, i2, j2 + 2),
                ];
                if quadratic {
                    for (a, b) in [
                        (i2 + 1, j2),
                        (i2 + 2, j2 + 1),
                        (i2 + 1, j2 + 2),
                        (i2, j2 + 1),
                    ] {
                        nodes.push(at(self, a, b));
                    }
                }
                let c = self.b.add_cell(self.kind, &nodes, self.label);
                self.label += 1;
                self.b.add_to_cell_group(body, c);
            }
        }
        for (group, i2, up) in [(inner, 0, false), (outer, 2 * ns, true)] {
            let Some(group) = group else { continue };
            for j in 0..nt {
                let (a, b) = (at(self, i2, 2 * j), at(self, i2, 2 * j + 2));
                let mut nodes = if up { vec![a, b] } else { vec![b, a] };
                if quadratic {
                    nodes.push(at(self, i2, 2 * j + 1));
                }
                let c = self.b.add_cell(edge, &nodes, self.label);
                self.label += 1;
                self.b.add_to_cell_group(group, c);
            }
        }
    }

    /// Nodes within 1e-9 of a point go in the node group `name`.
    pub fn node_group(&mut self, name: &str, test: impl Fn([f64; 2]) -> bool) {
        let hits: Vec<usize> = (0..self.b.num_nodes())
            .filter(|&n| test(self.b.coords()[n]))
            .collect();
        for n in hits {
            self.b.add_to_node_group(name, n);
        }
    }

    pub fn finish(self) -> Mesh {
        self.b.finish().unwrap()
    }
}

/// Point at angle θ on the boundary of the square of half-side h centred at the origin,
/// the sides' points spaced evenly along the side for evenly spaced θ (corners at 45°, …).
pub fn square_at(h: f64, th: f64) -> [f64; 2] {
    let q = std::f64::consts::FRAC_PI_2;
    let k = (th / q).round();
    let u = (th - k * q) / (q / 2.0); // in [-1, 1] along the side
    let (c, s) = ((k * q).cos(), (k * q).sin());
    [h * c - h * u * s, h * s + h * u * c]
}

/// The band between the closed curves `inner(θ)` and `outer(θ)` over θ ∈ [θ0, θ0 + span]
/// in n_r × n_t cells (s = 0 on `inner`), edges in the named groups.
#[allow(clippy::too_many_arguments)]
pub fn band(
    p: &mut Patches,
    (body, inner_group, outer_group): (&str, Option<&str>, Option<&str>),
    inner: &dyn Fn(f64) -> [f64; 2],
    outer: &dyn Fn(f64) -> [f64; 2],
    th0: f64,
    span: f64,
    n_r: usize,
    n_t: usize,
) {
    let map = |s: f64, t: f64| {
        let th = th0 + span * t;
        let (a, o) = (inner(th), outer(th));
        [a[0] + s * (o[0] - a[0]), a[1] + s * (o[1] - a[1])]
    };
    p.patch(n_r, n_t, &map, body, inner_group, outer_group);
}

/// Point at angle θ on the circle of radius r.
pub fn circle(r: f64) -> impl Fn(f64) -> [f64; 2] {
    move |th: f64| [r * th.cos(), r * th.sin()]
}
