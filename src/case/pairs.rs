//! The contact pairs of a case: options checked against the formulation, surfaces and
//! excluded nodes resolved on the mesh, scale-free defaults.

use super::schema::CaseFile;
use crate::contact::mortar::Mortar;
use crate::contact::pair::ContactPair;
use crate::contact::point_segment::{self, InitialStatus, Integration, PointToSegment};
use crate::contact::surface::Surface;
use crate::error::{Error, Result};
use crate::fem::material::Modelisation;
use crate::fem::solid::Kinematics;
use crate::mesh::Mesh;

/// The nodes of the node groups listed under `key` of a contact entry.
fn group_nodes(mesh: &Mesh, groups: &[String], what: &str, key: &str) -> Result<Vec<usize>> {
    let mut nodes = vec![];
    for g in groups {
        nodes.extend(
            mesh.node_group(g)
                .map_err(|e| Error::model(format!("{what}: {key}: {e}")))?,
        );
    }
    Ok(nodes)
}

/// The nodes of the node groups under `key`, each of which must be a node of `slave` (the
/// point-to-segment and node-to-segment multipliers live on slave nodes only).
fn slave_nodes(
    mesh: &Mesh,
    slave: &Surface,
    groups: &[String],
    what: &str,
    key: &str,
) -> Result<Vec<usize>> {
    let nodes = group_nodes(mesh, groups, what, key)?;
    if let Some(n) = nodes.iter().find(|n| slave.nodes.binary_search(n).is_err()) {
        return Err(Error::model(format!(
            "{what}: {key}: node {} is not on the slave surface '{}' (the contact points of \
             this formulation are on the slave surface only)",
            n + 1,
            slave.group
        )));
    }
    Ok(nodes)
}

/// The smallest Young's modulus of the case and the shortest cell chord of `slave`: the
/// scales of the contact parameters' defaults (no units in a default).
fn stiffness_scale(case: &CaseFile, mesh: &Mesh, slave: &Surface) -> (f64, f64) {
    let e_min = case
        .material
        .iter()
        .map(|m| m.young)
        .fold(f64::INFINITY, f64::min);
    (e_min, slave.shortest_cell(mesh))
}

/// The multiplier indices of `nodes` on a mortar pair: a node of the surface that carries
/// the multipliers, or one at the same place on the other surface (the pair may have put
/// the multipliers on the surface the user named master); Err(node) for a node on neither.
fn multiplier_indices(
    mesh: &Mesh,
    m: &Mortar,
    nodes: &[usize],
) -> std::result::Result<Vec<usize>, usize> {
    let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
    let tol = 1e-9 * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let mut out = vec![];
    for &n in nodes {
        if let Some(k) = m.mult_nodes.iter().position(|&s| s == n) {
            out.push(k);
            continue;
        }
        if !m.master.nodes.contains(&n) {
            return Err(n);
        }
        let x = mesh.coords[n];
        if let Some(k) = m.mult_nodes.iter().position(|&s| {
            let y = mesh.coords[s];
            (x[0] - y[0]).hypot(x[1] - y[1]) <= tol
        }) {
            out.push(k);
        }
    }
    Ok(out)
}

/// The multiplier nodes of a mortar pair on a line of symmetry: the node held at zero
/// along the axis nearest its surface's tangent by a [[displacement]], and so is the
/// nearest node of the other surface. Their relative slip is zero whatever the load, and
/// so is the shear, by symmetry; yet a friction multiplier there has a slave force on the
/// held component alone (the dual basis is biorthogonal) and meets the free dofs only
/// through the master's weak terms, so its stick law is near-singular and the stick/slip
/// branches cycle (a pin in a holed plate, half model, plate as slave: no convergence at
/// any step size). Such nodes are frictionless, as `friction_exclude` would make them
/// (SSNP154 excludes its axis node C so).
fn on_symmetry_lines(case: &CaseFile, mesh: &Mesh, m: &Mortar) -> Vec<usize> {
    let mut held = vec![[false; 2]; mesh.num_nodes()];
    for d in &case.displacement {
        let Ok(nodes) = mesh.node_group(&d.group) else {
            continue;
        };
        for (c, v) in [&d.dx, &d.dy].into_iter().enumerate() {
            if v.as_ref().and_then(|v| v.number()) == Some(0.0) {
                for &n in &nodes {
                    held[n][c] = true;
                }
            }
        }
    }
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let mut out = vec![];
    for (k, &n) in m.mult_nodes.iter().enumerate() {
        // |tangent| components summed over the node's cells (chord directions)
        let mut t = [0.0f64; 2];
        for &c in &m.slave.cells {
            let nodes = mesh.cell_nodes(c);
            if nodes.contains(&n) {
                let (a, b) = (mesh.coords[nodes[0]], mesh.coords[nodes[1]]);
                let l = dist(a, b);
                t[0] += (b[0] - a[0]).abs() / l;
                t[1] += (b[1] - a[1]).abs() / l;
            }
        }
        let axis = usize::from(t[1] > t[0]);
        let x = mesh.coords[n];
        let nearest = m
            .master
            .nodes
            .iter()
            .copied()
            .min_by(|&a, &b| dist(mesh.coords[a], x).total_cmp(&dist(mesh.coords[b], x)));
        if held[n][axis] && nearest.is_some_and(|q| held[q][axis]) {
            out.push(k);
        }
    }
    out
}

/// For two surfaces of one body: the slave node that lies deepest behind the master (its
/// nearest orthogonal projection on a master chord on the inner side of the master's
/// outward normal), when deeper than half the shortest slave chord: (node, depth). Two
/// surfaces that face away from each other (a body's top and bottom) are so: between two
/// bodies the overlap check refuses it, but here the slave node is on the boundary of the
/// master's own body, not inside it.
fn behind_master(mesh: &Mesh, slave: &Surface, master: &Surface) -> Option<(usize, f64)> {
    let chord = |c: usize| {
        let n = mesh.cell_nodes(c);
        (mesh.coords[n[0]], mesh.coords[n[1]])
    };
    let h = slave.shortest_cell(mesh);
    let mut worst: Option<(usize, f64)> = None;
    for &n in &slave.nodes {
        if master.nodes.binary_search(&n).is_ok() {
            continue;
        }
        let p = mesh.coords[n];
        // (distance, signed gap) of the nearest orthogonal projection
        let mut nearest: Option<(f64, f64)> = None;
        for (k, &c) in master.cells.iter().enumerate() {
            let (a, b) = chord(c);
            let t = [b[0] - a[0], b[1] - a[1]];
            let l2 = t[0] * t[0] + t[1] * t[1];
            let s = ((p[0] - a[0]) * t[0] + (p[1] - a[1]) * t[1]) / l2;
            if !(0.0..=1.0).contains(&s) {
                continue;
            }
            let d = [p[0] - a[0] - s * t[0], p[1] - a[1] - s * t[1]];
            let sign = if master.ccw[k] { 1.0 } else { -1.0 };
            let gap = sign * (d[0] * t[1] - d[1] * t[0]) / l2.sqrt();
            let dist = d[0].hypot(d[1]);
            if nearest.is_none_or(|(m, _)| dist < m) {
                nearest = Some((dist, gap));
            }
        }
        if let Some((_, gap)) = nearest.filter(|&(_, g)| g < -0.5 * h) {
            if worst.is_none_or(|(_, w)| -gap > w) {
                worst = Some((n, -gap));
            }
        }
    }
    worst
}

/// The contact pairs of a case.
pub fn build_pairs(case: &CaseFile, mesh: &Mesh) -> Result<Vec<Box<dyn ContactPair>>> {
    let mut pairs: Vec<Box<dyn ContactPair>> = vec![];
    // per cell, the compliance of its material (1 when it has none: an obstacle's cells
    // all have one, but a malformed case is reported elsewhere)
    let mut compliance = vec![1.0; mesh.num_cells()];
    for spec in &case.material {
        let c = match case.model.modelisation {
            Modelisation::PlaneStress => 1.0 / spec.young,
            _ => (1.0 - spec.nu * spec.nu) / spec.young,
        };
        if let Ok(cells) = spec.cells(mesh) {
            for cell in cells {
                compliance[cell] = c;
            }
        }
    }
    let bodies = crate::mesh::topology::node_bodies(mesh);
    let rigid = super::rigid::bodies(case, mesh)?;
    for (i, c) in case.contact.iter().enumerate() {
        let what = format!("[[contact]] {} ({} on {})", i + 1, c.slave, c.master);
        if c.slave == c.master {
            return Err(Error::model(format!(
                "{what}: slave and master must be different groups"
            )));
        }
        if let Some(b) = rigid.iter().find(|b| b.group == c.slave) {
            return Err(Error::model(format!(
                "{what}: the slave '{}' is the rigid surface {}: a rigid surface can only be \
                 the master of a pair (the multipliers live on a deformable slave)",
                c.slave, b.what
            )));
        }
        let slave = Surface::from_group(mesh, &c.slave, "slave")
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        let master = match rigid.iter().find(|b| b.group == c.master) {
            Some(b) => Surface::rigid(mesh, &c.master, b.made, &slave.nodes),
            None => Surface::from_group(mesh, &c.master, "master"),
        }
        .map_err(|e| Error::model(format!("{what}: {e}")))?;
        // Two edge groups of one connected mesh (a body cut along a line, bodies sharing
        // nodes) may be in contact; a node of both surfaces (where a cut ends) would be in
        // contact with itself, its gap zero whatever the motion and its multiplier free: it
        // is left out of contact as `exclude` would.
        let shared: Vec<usize> = slave
            .nodes
            .iter()
            .copied()
            .filter(|n| master.nodes.binary_search(n).is_ok())
            .collect();
        if shared.len() == slave.nodes.len() || shared.len() == master.nodes.len() {
            return Err(Error::model(format!(
                "{what}: every node of '{}' is also a node of '{}': the surfaces must be \
                 distinct (self-contact of one surface folding onto itself is not supported)",
                if shared.len() == slave.nodes.len() {
                    &c.slave
                } else {
                    &c.master
                },
                if shared.len() == slave.nodes.len() {
                    &c.master
                } else {
                    &c.slave
                },
            )));
        }
        // (checked after the options, so that their errors come first)
        let one_body = || -> Result<()> {
            if shared.is_empty() {
                let of = |s: &Surface| -> std::collections::BTreeSet<usize> {
                    s.nodes.iter().map(|&n| bodies[n]).collect()
                };
                if of(&slave).is_disjoint(&of(&master)) {
                    return Ok(());
                }
            }
            let Some((n, depth)) = behind_master(mesh, &slave, &master)
                .or_else(|| behind_master(mesh, &master, &slave))
            else {
                return Ok(());
            };
            Err(Error::model(format!(
                "{what}: '{}' and '{}' are surfaces of one body that face away from each \
                 other: node {} lies {depth:.3e} behind the other surface, inside the body \
                 (contact inside one mesh is between surfaces that face each other across a \
                 cut or a gap)",
                c.slave,
                c.master,
                n + 1
            )))
        };
        let integration = match c.integration.as_str() {
            "gauss" if (1..=10).contains(&c.gauss_points) => Integration::Gauss(c.gauss_points),
            "gauss" => {
                return Err(Error::model(format!(
                    "{what}: gauss_points must be 1 to 10, got {}",
                    c.gauss_points
                )))
            }
            "nodal" => Integration::Nodal,
            other => {
                return Err(Error::model(format!(
                    "{what}: integration '{other}' is not one of gauss, nodal"
                )))
            }
        };
        let mortar = c.formulation == "mortar";
        // mortar's default start is the touching nodes, the others' every point
        let initial_name = c.initial.as_deref().unwrap_or(if mortar {
            "touching (the default)"
        } else {
            "all"
        });
        let initial = match c.initial.as_deref().unwrap_or("all") {
            "all" if c.initial.is_none() && mortar => InitialStatus::Closed,
            "all" => InitialStatus::All,
            "closed" => InitialStatus::Closed,
            other => {
                return Err(Error::model(format!(
                    "{what}: initial '{other}' is not one of all, closed"
                )))
            }
        };
        if let Some(g) = c.initial_gap {
            if g.is_nan() || g < 0.0 || c.initial.as_deref() != Some("closed") {
                return Err(Error::model(format!(
                    "{what}: initial_gap must be 0 or positive and goes with initial = \"closed\", got {g} \
                     with initial = \"{initial_name}\""
                )));
            }
        }
        if c.friction.is_nan() || c.friction < 0.0 {
            return Err(Error::model(format!(
                "{what}: friction must be 0 or positive, got {}",
                c.friction
            )));
        }
        // (μ μ p overflows long before; an interface that never slips needs a μ of a few)
        if c.friction > 1e6 {
            return Err(Error::model(format!(
                "{what}: friction = {:e} is beyond any Coulomb coefficient (at most 1e6; an \
                 interface that never slips needs a μ of a few, e.g. 10)",
                c.friction
            )));
        }
        if let Some(a) = c.adjust {
            if !(a.is_finite() && a >= 0.0) || c.formulation != "mortar" {
                return Err(Error::model(format!(
                    "{what}: adjust (a distance: initial gaps and overlaps up to it are removed) \
                     must be finite and 0 or positive and goes with formulation = \"mortar\", \
                     got {a} with formulation = \"{}\"",
                    c.formulation
                )));
            }
        }
        let node_to_segment = c.formulation == "node-to-segment";
        if node_to_segment && c.gauss_points != 3 {
            return Err(Error::model(format!(
                "{what}: gauss_points does nothing with formulation = \"node-to-segment\" (one \
                 contact point per slave node)"
            )));
        }
        if !node_to_segment && c.penalty.is_some() {
            return Err(Error::model(format!(
                "{what}: penalty goes with formulation = \"node-to-segment\""
            )));
        }
        if c.tangential_penalty.is_some() && !(node_to_segment && c.friction > 0.0) {
            return Err(Error::model(format!(
                "{what}: tangential_penalty (a stick stiffness) goes with formulation = \
                 \"node-to-segment\" and friction > 0"
            )));
        }
        if let Some(k) = c.tangential_penalty {
            if !(k.is_finite() && k > 0.0) {
                return Err(Error::model(format!(
                    "{what}: tangential_penalty must be a positive number, got {k}"
                )));
            }
        }
        if let Some(k) = c.penalty {
            if k.is_nan() || k <= 0.0 {
                return Err(Error::model(format!(
                    "{what}: penalty must be positive, got {k}"
                )));
            }
        }
        match c.formulation.as_str() {
            "point-to-segment" | "node-to-segment" => {}
            "mortar" => {
                one_body()?;
                // (a rigid master keeps the multipliers on the deformable slave)
                let (mut slave, mut master) = if master.is_rigid() {
                    (slave, master)
                } else {
                    let (s, m, _) = crate::contact::mortar::multiplier_side(mesh, slave, master);
                    (s, m)
                };
                // Across a cut, the multipliers go on the lip finer at the shared node: the
                // shared node carries none, and the constant pressure stays in the weak
                // space only where the multiplier side's cell there lies within the other's
                // (the patch test is exact then; else off by that cell's share).
                if !shared.is_empty() {
                    let end = |s: &Surface| -> f64 {
                        s.cells
                            .iter()
                            .map(|&e| mesh.cell_nodes(e))
                            .filter(|n| n.iter().any(|k| shared.contains(k)))
                            .map(|n| {
                                let (a, b) = (mesh.coords[n[0]], mesh.coords[n[1]]);
                                (a[0] - b[0]).hypot(a[1] - b[1])
                            })
                            .fold(f64::INFINITY, f64::min)
                    };
                    if end(&slave) > (1.0 + 1e-9) * end(&master) {
                        std::mem::swap(&mut slave, &mut master);
                    }
                }
                // complementarity parameter: the softest E over the shortest slave cell
                let (e_min, h_min) = stiffness_scale(case, mesh, &slave);
                // adjust absorbs a discretisation mismatch, a fraction of a cell; removing a
                // cell's worth or more would hide a real gap or overlap
                if let Some(a) = c.adjust.filter(|&a| a >= h_min) {
                    return Err(Error::model(format!(
                        "{what}: adjust = {a:e} must be below the smallest slave cell size h = \
                         {h_min:.4e} of the pair (it removes the gaps and overlaps of surfaces \
                         discretised differently, a fraction of a cell; a cell's worth or more \
                         is a real gap or overlap)"
                    )));
                }
                let mut mortar = Mortar::new(
                    mesh,
                    slave,
                    master,
                    e_min / h_min,
                    case.model.modelisation,
                    case.model.thickness,
                    case.model.kinematics == Kinematics::Small,
                );
                mortar.initial_gap = c.initial_gap;
                mortar.adjust = c.adjust;
                mortar.initial_all = c.initial.as_deref() == Some("all");
                let of = |s: &Surface| -> Vec<f64> {
                    s.parent.iter().map(|&p| compliance[p]).collect()
                };
                // (a rigid master: no compliance, the interface normal is its own)
                let master_compliance = if mortar.master.is_rigid() {
                    vec![0.0; mortar.master.cells.len()]
                } else {
                    of(&mortar.master)
                };
                mortar.compliance = (of(&mortar.slave), master_compliance);
                // a micro-strain of the softest body: below it a pressure is round-off
                mortar.pressure_floor = 1e-6 * e_min;
                // exclude names slave nodes; where the multipliers went to the master
                // surface (the coarser one), the multiplier node at the same place
                let mut nodes = group_nodes(mesh, &c.exclude, &what, "exclude")?;
                nodes.extend(shared.iter().filter(|n| !nodes.contains(n)).collect::<Vec<_>>());
                for &n in &nodes {
                    let k = match multiplier_indices(mesh, &mortar, &[n]) {
                        Ok(k) if !k.is_empty() => k[0],
                        _ => {
                            return Err(Error::model(format!(
                                "{what}: exclude: node {} is not a node of the surface that \
                                 carries the mortar multipliers, nor at the place of one (the \
                                 multipliers are on '{}', the coarser surface)",
                                n + 1,
                                mortar.slave.group
                            )))
                        }
                    };
                    if !mortar.contact_excluded.contains(&k) {
                        mortar.contact_excluded.push(k);
                        mortar.excluded_nodes.push(mortar.mult_nodes[k]);
                    }
                }
                if c.friction > 0.0 {
                    mortar.friction = Some(c.friction);
                    let nodes = group_nodes(mesh, &c.friction_exclude, &what, "friction_exclude")?;
                    let mut excluded = multiplier_indices(mesh, &mortar, &nodes).map_err(|n| {
                        Error::model(format!(
                            "{what}: friction_exclude: node {} is on neither contact surface",
                            n + 1
                        ))
                    })?;
                    excluded.extend(on_symmetry_lines(case, mesh, &mortar));
                    excluded.sort_unstable();
                    excluded.dedup();
                    mortar.friction_excluded = excluded;
                }
                pairs.push(Box::new(mortar));
                continue;
            }
            other => {
                return Err(Error::model(format!(
                    "{what}: formulation '{other}' is not one of point-to-segment, node-to-segment, mortar"
                )))
            }
        }
        // scale-free defaults: the softest body's modulus over the shortest slave cell
        let (e_min, h_min) = stiffness_scale(case, mesh, &slave);
        let friction_excluded =
            slave_nodes(mesh, &slave, &c.friction_exclude, &what, "friction_exclude")?;
        let mut contact_excluded = slave_nodes(mesh, &slave, &c.exclude, &what, "exclude")?;
        for &n in &shared {
            if !contact_excluded.contains(&n) {
                contact_excluded.push(n);
            }
        }
        let opts = point_segment::Options {
            integration,
            node_to_segment,
            penalty: c.penalty,
            contact_excluded,
            rho: c.rho.unwrap_or(1e-3 * e_min / h_min),
            initial,
            initial_gap: c.initial_gap,
            friction: (c.friction > 0.0).then_some(c.friction),
            rho_f: c.rho_f.unwrap_or(60.0 / h_min),
            trial_stiffness: e_min / h_min,
            friction_excluded,
            tangential_penalty: c.tangential_penalty,
            smoothed_normal: match c.master_normal.as_deref() {
                None | Some("smoothed") => true,
                Some("segment") => false,
                Some(other) => {
                    return Err(Error::model(format!(
                        "{what}: master_normal '{other}' is not one of smoothed, segment"
                    )))
                }
            },
            ..Default::default()
        };
        one_body()?;
        let mut pair = PointToSegment::new(
            mesh,
            slave,
            master,
            opts,
            case.model.modelisation,
            case.model.thickness,
        );
        // node-to-segment multipliers are nodal forces: its augmentation is a stiffness
        // (force / length), 1e-3 E_min/h times a node's mean share of the surface (h times
        // the thickness, or 2πr), so that it is the same in any units (in stress / length
        // it was 1e3 times stiffer in N-m-Pa than in N-mm-MPa, and two discs diverged)
        if node_to_segment && c.rho.is_none() {
            pair.opts.rho *= pair.mean_node_share();
        }
        pairs.push(Box::new(pair));
    }
    Ok(pairs)
}
