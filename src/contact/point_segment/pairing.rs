//! Pairing each contact point with a master cell (nearest master node, then the cells
//! around it, with hysteresis and a reach), growing the candidates, and the geometry of a
//! point on its paired cell: projection, normal, gap.

use super::super::overlap::geometry::{inside, P};
use super::super::projection::{point_and_tangent, project};
use super::super::smoothed_normal::smoothed_frame;
use super::{
    anticipated_candidates, Eval, PointToSegment, CANDIDATE_MARGIN, PAIRING_HYSTERESIS,
    PAIRING_REACH,
};
use crate::fem::element::{shape, shape_grad, MAX_NODES};
use crate::mesh::Mesh;

impl PointToSegment {
    pub(super) fn current(mesh: &Mesh, u: &[f64], n: usize) -> [f64; 2] {
        [
            mesh.coords[n][0] + u[2 * n],
            mesh.coords[n][1] + u[2 * n + 1],
        ]
    }

    fn slave_point(&self, mesh: &Mesh, u: &[f64], i: usize, ns: &mut [f64; MAX_NODES]) -> [f64; 2] {
        let p = &self.points[i];
        let c = self.slave.cells[p.cell];
        let kind = mesh.kind(c);
        shape(kind, [p.xi, 0.0], ns);
        let mut x = [0.0; 2];
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            let xn = Self::current(mesh, u, n);
            x[0] += ns[a] * xn[0];
            x[1] += ns[a] * xn[1];
        }
        x
    }

    /// Pairs point i with the master surface at displacement u. With `keep`, a point stays
    /// with its master cell while its projection lies on the cell or within
    /// PAIRING_HYSTERESIS of its ends: a point at a master vertex (a slave node on a master
    /// node, as on conforming meshes) is otherwise paired with one cell and the other in
    /// turn as round-off moves it, each with its own normal, and Newton stalls between the
    /// two (conforming rings: the residual frozen at 1.5e-2).
    ///
    /// A point behind the master surface and inside the master body (bounded by `body`, its
    /// deformed boundary pieces) pairs however many cells deep: an overlap has to be seen
    /// to be undone. One beyond the body is a body passing through, not contact. With
    /// `any_distance`, a point pairs however far it is (for the linearised statuses).
    pub(super) fn pair(
        &mut self,
        mesh: &Mesh,
        u: &[f64],
        i: usize,
        keep: bool,
        body: &[(P, P)],
        any_distance: bool,
    ) {
        let mut ns = [0.0; MAX_NODES];
        let xs = self.slave_point(mesh, u, i, &mut ns);
        // (whether xs lies behind master cell im at q, where its tangent is t)
        let behind = |im: usize, q: [f64; 2], t: [f64; 2]| {
            let side = (xs[0] - q[0]) * t[1] - (xs[1] - q[1]) * t[0];
            if self.master.ccw[im] {
                side < 0.0
            } else {
                side > 0.0
            }
        };
        if keep && !self.points[i].excluded {
            let c = self.master.cells[self.points[i].master];
            let x: Vec<[f64; 2]> = mesh
                .cell_nodes(c)
                .iter()
                .map(|&n| Self::current(mesh, u, n))
                .collect();
            let xi = project(mesh.kind(c), &x, xs).xi;
            let (q, t) = point_and_tangent(mesh.kind(c), &x, xi.clamp(-1.0, 1.0));
            // (a point gone beyond reach is paired again, i.e. left unpaired, below)
            let dist = (q[0] - xs[0]).hypot(q[1] - xs[1]);
            let im = self.points[i].master;
            let near = any_distance
                || dist <= PAIRING_REACH * t[0].hypot(t[1])
                || (behind(im, q, t) && inside(xs, body));
            if near && xi.abs() <= 1.0 + PAIRING_HYSTERESIS {
                self.points[i].xi_m = xi.clamp(-1.0, 1.0);
                return;
            }
        }
        let nearest = self
            .master
            .nodes
            .iter()
            .copied()
            .min_by(|&a, &b| {
                let (pa, pb) = (Self::current(mesh, u, a), Self::current(mesh, u, b));
                let da = (pa[0] - xs[0]).powi(2) + (pa[1] - xs[1]).powi(2);
                let db = (pb[0] - xs[0]).powi(2) + (pb[1] - xs[1]).powi(2);
                da.total_cmp(&db)
            })
            .unwrap();
        // (dist², master, ξ clamped, overshoot, behind)
        let mut best: Option<(f64, usize, f64, f64, bool)> = None;
        for &im in self
            .master_cells_of_node
            .get(&nearest)
            .map(|v| v.as_slice())
            .unwrap_or(&[])
        {
            let c = self.master.cells[im];
            let kind = mesh.kind(c);
            let x: Vec<[f64; 2]> = mesh
                .cell_nodes(c)
                .iter()
                .map(|&n| Self::current(mesh, u, n))
                .collect();
            let pr = project(kind, &x, xs);
            let xi = pr.xi.clamp(-1.0, 1.0);
            let over = (pr.xi.abs() - 1.0).max(0.0);
            let (q, t) = point_and_tangent(kind, &x, xi);
            let d2 = (q[0] - xs[0]).powi(2) + (q[1] - xs[1]).powi(2);
            if best.is_none_or(|b| d2 < b.0) {
                best = Some((d2, im, xi, over, behind(im, q, t)));
            }
        }
        // A point farther from the master surface than PAIRING_REACH times the larger of
        // its cell and the nearest master cell stays unpaired (inactive, no couplings):
        // the pattern, and so the contact interface the solver condenses on, then holds
        // only the part of the slave surface within reach. Pairing is redone at every
        // status update, so a point that comes within reach is paired (and may close)
        // there.
        let length = |c: usize| {
            let nodes = mesh.cell_nodes(c);
            let (a, b) = (
                Self::current(mesh, u, nodes[0]),
                Self::current(mesh, u, nodes[1]),
            );
            (a[0] - b[0]).hypot(a[1] - b[1])
        };
        let ic = self.points[i].cell;
        // (the last flag now: paired beyond reach, as an overlap)
        let best = best.and_then(|(d2, im, xi, over, behind)| {
            let reach =
                PAIRING_REACH * length(self.slave.cells[ic]).max(length(self.master.cells[im]));
            if any_distance || d2 <= reach * reach {
                Some((d2, im, xi, over, false))
            } else {
                (behind && inside(xs, body)).then_some((d2, im, xi, over, true))
            }
        });
        // The pattern takes in the point's cell when the point is within the candidates'
        // margin of it (of the smaller cell), or in contact: a point paired farther is
        // open and couples nothing, and a far coarse slave cell paired with a coarse master
        // cell would bring the fine cells around into the contact interface for nothing.
        // An overlapping point is about to close.
        if let Some((d2, im, _, _, overlap)) = best {
            let reserve =
                CANDIDATE_MARGIN * length(self.slave.cells[ic]).min(length(self.master.cells[im]));
            let near = d2 <= reserve * reserve || self.points[i].active || overlap;
            if near && !self.candidates[ic].contains(&im) {
                self.add_candidates(mesh, ic, im);
            }
        }
        let p = &mut self.points[i];
        match best {
            Some((_, im, xi, over, _)) => {
                p.master = im;
                p.xi_m = xi;
                p.excluded = p.left_out || over > self.opts.projection_tolerance;
            }
            None => p.excluded = true,
        }
    }

    /// Adds master cell `im` and its neighbours up to two cells away along the master
    /// surface to the candidates of slave cell `ic`: a point slides to a neighbouring
    /// master cell far more often than it jumps, and a pattern that already holds the
    /// neighbours keeps the symbolic factorisation (≈ 2 numeric ones) from being redone.
    pub(super) fn add_candidates(&mut self, mesh: &Mesh, ic: usize, im: usize) {
        let mut ring = vec![im];
        for _ in 0..2 {
            let mut next = ring.clone();
            for &m in &ring {
                for &n in mesh.cell_nodes(self.master.cells[m]) {
                    next.extend(self.master_cells_of_node.get(&n).into_iter().flatten());
                }
            }
            next.sort_unstable();
            next.dedup();
            ring = next;
        }
        let list = &mut self.candidates[ic];
        for m in ring {
            if !list.contains(&m) {
                list.push(m);
            }
        }
        self.candidates_generation += 1;
    }

    /// Adds to each slave cell's candidates those anticipated at displacement u
    /// (`anticipated_candidates`: within reach there, as the initial candidates on the
    /// initial geometry, and within `reach` of it unless that takes in too much).
    pub(super) fn anticipate(&mut self, mesh: &Mesh, u: &[f64], reach: f64) {
        let surfaces = (&self.slave, &self.master);
        let found = anticipated_candidates(
            mesh,
            u,
            surfaces,
            (CANDIDATE_MARGIN, reach),
            &self.candidates,
        );
        let mut grew = false;
        for (list, more) in self.candidates.iter_mut().zip(found) {
            for m in more {
                if !list.contains(&m) {
                    list.push(m);
                    grew = true;
                }
            }
        }
        if grew {
            self.candidates_generation += 1;
        }
    }

    /// Geometry of point i at displacement u: projected again on its paired master cell
    /// (the cell only changes in `update_status`), so that the residual is a smooth
    /// function of u between status updates and the tangent below is its exact derivative.
    pub(super) fn eval(&self, mesh: &Mesh, u: &[f64], i: usize) -> Eval {
        let mut ns = [0.0; MAX_NODES];
        let xs = self.slave_point(mesh, u, i, &mut ns);
        let p = &self.points[i];
        let c = self.master.cells[p.master];
        let kind = mesh.kind(c);
        let nm_nodes = kind.num_nodes();
        let mut x = [[0.0; 2]; 3];
        for (a, &n) in mesh.cell_nodes(c).iter().enumerate() {
            x[a] = Self::current(mesh, u, n);
        }
        let raw = project(kind, &x[..nm_nodes], xs).xi;
        let clamped = raw.abs() > 1.0;
        let xi_m = raw.clamp(-1.0, 1.0);
        let (q, t) = point_and_tangent(kind, &x[..nm_nodes], xi_m);
        let lt = t[0].hypot(t[1]);
        let tau = [t[0] / lt, t[1] / lt];
        // outward normal of the master body, then inward
        let out = if self.master.ccw[p.master] {
            [tau[1], -tau[0]]
        } else {
            [-tau[1], tau[0]]
        };
        let seg_normal = [-out[0], -out[1]];
        let d_seg = (xs[0] - q[0]) * seg_normal[0] + (xs[1] - q[1]) * seg_normal[1];
        // A straight master cell's normal jumps at its vertices by the angle between cells
        // (a polygon standing for a curve): the gap and force take the normal interpolated
        // between the vertices' averaged normals instead, continuous along the surface, so
        // that a slave node at a vertex (conforming meshes) is pushed along the bisector,
        // not along one cell's normal or the other's (conforming rings: a tangential bias
        // of the pressure, -1.4 % to +2.7 % around the ring). Straight in-line cells keep
        // their normal; curved (Seg3) cells meet with continuous normals already.
        let smoothed = nm_nodes == 2 && self.opts.smoothed_normal;
        let (normal, tau) = if smoothed {
            let at = |n: usize| Self::current(mesh, u, n);
            let (n, tau, _) = smoothed_frame(
                mesh,
                &self.master,
                &self.master_cells_of_node,
                &at,
                p.master,
                xi_m,
                None,
            );
            (n, tau)
        } else {
            (seg_normal, tau)
        };
        let d = (xs[0] - q[0]) * normal[0] + (xs[1] - q[1]) * normal[1];
        let mut nm = [0.0; MAX_NODES];
        let mut dnm = [[0.0; 2]; MAX_NODES];
        shape(kind, [xi_m, 0.0], &mut nm);
        shape_grad(kind, [xi_m, 0.0], &mut dnm);
        // second derivative of the master curve (constant on a Seg3, zero on a Seg2)
        let tt = if nm_nodes == 3 {
            [
                x[0][0] + x[1][0] - 2.0 * x[2][0],
                x[0][1] + x[1][1] - 2.0 * x[2][1],
            ]
        } else {
            [0.0, 0.0]
        };
        Eval {
            ns,
            nm,
            dnm: std::array::from_fn(|a| dnm[a][0]),
            normal,
            tau,
            t,
            tt,
            d,
            clamped,
            seg_normal,
            d_seg,
            tn: t[0] * normal[0] + t[1] * normal[1],
            tq: (xs[0] - q[0]) * tau[0] + (xs[1] - q[1]) * tau[1],
            xi_m,
            smoothed,
        }
    }

    pub(super) fn point_lambda(
        &self,
        mesh: &Mesh,
        i: usize,
        ns: &[f64; MAX_NODES],
        lam: &[f64],
    ) -> f64 {
        let c = self.slave.cells[self.points[i].cell];
        mesh.cell_nodes(c)
            .iter()
            .enumerate()
            .map(|(a, n)| ns[a] * lam[self.mult_of[n]])
            .sum()
    }

    /// Open gap below which a point counts as initially touching: 1e-3 of the shortest
    /// slave cell (so that the Gauss point nearest a single initial contact point is closed).
    pub(super) fn touch_tolerance(&self, mesh: &Mesh) -> f64 {
        1e-3 * self.slave.shortest_cell(mesh)
    }

    /// Re-pairs every point at the displacement u.
    pub fn pair_all(&mut self, mesh: &Mesh, u: &[f64]) {
        // The master body on the current geometry. (Within two cells alone, SSNP154 A at
        // 320k unknowns, cells of 0.033 mm, lost the points its second step's first
        // corrections carried deeper: 58 Newton iterations, now 24.)
        let at = |n: usize| Self::current(mesh, u, n);
        let body: Vec<(P, P)> = self
            .master_pieces
            .iter()
            .map(|&[a, b]| (at(a), at(b)))
            .collect();
        for i in 0..self.points.len() {
            self.pair(mesh, u, i, true, &body, false);
        }
    }
}
