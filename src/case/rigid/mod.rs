//! Rigid surfaces (`[[rigid]]`): masters of contact pairs that move as a whole with a
//! reference point R, whose three dofs (ux, uy, rotation θ) are imposed, driven by a force
//! or a moment (then unknowns), or held at 0.
//!
//! Design: the surface is an edge group of the mesh (given, or made here from a line or a
//! circle, `geometry.rs`) and R is a node: a mesh node of no 2D cell, or a node added at
//! the reference point; θ is the x dof of one more added node (its y dof is held). Every
//! surface node's dofs are then *linked* to R's in the dof map (`DofMap::set_link`):
//!   u_n = u_R + (R(θ) − I)(X_n − X_R)   θ imposed: the rotation part is an imposed value
//!                                       (`Imposed::Follow`, exact rotation, any kinematics)
//!   u_n = u_R + θ ẑ × (X_n − X_R)       θ driven by a moment: linear in θ (small kinematics)
//! This fits the code as it is: the contact formulations see ordinary master nodes (no
//! change in any of them, every formulation works), the coupled matrix already condenses
//! contributions on linked dofs onto the unknowns they depend on (Tᵀ K T), loads on R are
//! nodal forces, and imposed motions go through the same time functions and expressions as
//! `[[displacement]]`. Extra unknowns beside the 2-dofs-per-node numbering would have
//! touched every vector of the code; eliminating the master nodes inside each formulation
//! would have touched all three. A moment-driven rotation with large kinematics would need
//! a link non-linear in an unknown (and its second derivative in the tangent): refused.
//!
//! The reaction at R (force and moment the driver exerts on the surface, about R) is the
//! condensed contact force on the surface nodes: with force control it balances the applied
//! force, with an imposed motion it is the support's reaction.
//!
//! | file | what |
//! |---|---|
//! | `geometry.rs` | the mesh with the lines', circles' edges and the reference nodes added |

mod geometry;

pub use geometry::augment;

use super::schema::{CaseFile, RigidSpec};
use crate::assembly::dofs::DofMap;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// A `[[rigid]]` entry resolved on the (augmented) mesh.
#[derive(Clone, Debug)]
pub struct RigidBody {
    /// `[[rigid]] 'name'`, for messages.
    pub what: String,
    pub name: String,
    /// The edge group of the surface (the name a [[contact]] master gives).
    pub group: String,
    /// The surface's nodes, sorted.
    pub nodes: Vec<usize>,
    pub reference: [f64; 2],
    /// The node whose dofs are ux, uy of the reference point.
    pub ref_node: usize,
    /// The node whose x dof is the rotation.
    pub rot_node: usize,
    /// Whether the rotation is an unknown (driven by a moment).
    pub rotation_free: bool,
    /// Whether the surface was made here (its cells run with the outward normal on the
    /// right) rather than given by the mesh.
    pub made: bool,
}

/// The name of an entry: `name`, else its group.
pub fn name_of(spec: &RigidSpec, i: usize) -> Result<String> {
    match (&spec.name, &spec.group) {
        (Some(n), _) => Ok(n.clone()),
        (None, Some(g)) => Ok(g.clone()),
        (None, None) => Err(Error::model(format!(
            "[[rigid]] {}: a line or a circle needs a name (the master of its [[contact]])",
            i + 1
        ))),
    }
}

/// The node group of the node added at the reference point of entry `name`, and of the
/// node carrying its rotation.
fn reference_group(name: &str) -> String {
    format!("{name} (rigid reference)")
}
fn rotation_group(name: &str) -> String {
    format!("{name} (rigid rotation)")
}

/// The rigid surfaces of a case on the mesh `augment` made.
pub fn bodies(case: &CaseFile, mesh: &Mesh) -> Result<Vec<RigidBody>> {
    let mut out: Vec<RigidBody> = vec![];
    for (i, spec) in case.rigid.iter().enumerate() {
        let name = name_of(spec, i)?;
        let what = format!("[[rigid]] '{name}'");
        let group = spec.group.clone().unwrap_or_else(|| name.clone());
        let missing = || {
            Error::model(format!(
                "{what}: the mesh has no reference node for it (the mesh must go through \
                 case::rigid::augment, as case::run does)"
            ))
        };
        let ref_node = match &spec.reference_node {
            Some(g) => mesh
                .single_node(g)
                .map_err(|e| Error::model(format!("{what}: reference_node: {e}")))?,
            None => mesh
                .single_node(&reference_group(&name))
                .map_err(|_| missing())?,
        };
        let rot_node = mesh
            .single_node(&rotation_group(&name))
            .map_err(|_| missing())?;
        let nodes = mesh
            .node_group(&group)
            .map_err(|e| Error::model(format!("{what}: {e}")))?;
        out.push(RigidBody {
            what,
            name,
            group,
            nodes,
            reference: mesh.coords[ref_node],
            ref_node,
            rot_node,
            rotation_free: spec.moment.is_some(),
            made: spec.group.is_none(),
        });
    }
    if let Some(b) = out
        .iter()
        .find(|b| !case.contact.iter().any(|c| c.master == b.group))
    {
        return Err(Error::model(format!(
            "{} is the master of no [[contact]] (give a [[contact]] with master = \"{}\"): a \
             rigid surface acts through contact only",
            b.what, b.group
        )));
    }
    check_exclusive(case, mesh, &out)?;
    Ok(out)
}

/// A rigid surface's nodes move with it alone: no other entry may impose, load or relate
/// them, and two rigid surfaces share no node.
fn check_exclusive(case: &CaseFile, mesh: &Mesh, bodies: &[RigidBody]) -> Result<()> {
    let mut owner = std::collections::HashMap::new();
    for (k, b) in bodies.iter().enumerate() {
        for &n in b.nodes.iter().chain([&b.ref_node]) {
            if let Some(j) = owner.insert(n, k).filter(|&j| j != k) {
                return Err(Error::model(format!(
                    "{}: node {} is also a node of {}: rigid surfaces share no node",
                    b.what,
                    n + 1,
                    bodies[j].what
                )));
            }
        }
    }
    let mut groups: Vec<(String, &str)> = vec![];
    for d in &case.displacement {
        groups.push((format!("[[displacement]] on '{}'", d.group), &d.group));
    }
    for r in &case.rotation {
        groups.push((format!("[[rotation]] on '{}'", r.group), &r.group));
    }
    for f in &case.force {
        groups.push((format!("[[force]] on '{}'", f.group), &f.group));
    }
    for r in &case.relation {
        for t in &r.terms {
            groups.push((format!("[[relation]] '{}'", r.name), &t.group));
        }
    }
    for (entry, g) in groups {
        let Ok(nodes) = mesh.node_group(g) else {
            continue; // (reported by the entry itself)
        };
        if let Some((n, k)) = nodes.iter().find_map(|n| owner.get(n).map(|&k| (*n, k))) {
            return Err(Error::model(format!(
                "{entry}: node {} belongs to the rigid surface {}, which moves with its \
                 reference point only (give its motion or load in the [[rigid]] entry)",
                n + 1,
                bodies[k].what
            )));
        }
    }
    Ok(())
}

/// Links every surface node's dofs to the reference point's (see the module header).
pub fn link(dofs: &mut DofMap, mesh: &Mesh, bodies: &[RigidBody]) {
    for b in bodies {
        let [xr, yr] = b.reference;
        for &n in &b.nodes {
            if n == b.ref_node {
                continue;
            }
            let x = mesh.coords[n];
            let arm = [-(x[1] - yr), x[0] - xr]; // ẑ × (X − X_R)
            for c in 0..2 {
                let mut combo = vec![(2 * b.ref_node + c, 1.0)];
                if b.rotation_free {
                    combo.push((2 * b.rot_node, arm[c]));
                }
                dofs.set_link(2 * n + c, &combo, !b.rotation_free);
            }
        }
    }
}

/// The state of a rigid surface at a converged time.
#[derive(Clone, Debug)]
pub struct RigidState {
    pub name: String,
    /// ux, uy, rotation of the reference point.
    pub motion: [f64; 3],
    /// Force and moment (about the reference point) the driver exerts on the surface.
    pub reaction: [f64; 3],
}

/// The states from the full displacement `u`, the residual f_int + contact − f_ext and the
/// external forces (f_int + contact is the force on each node; surface nodes have no
/// f_int); `current`: moments with the current arms (large kinematics), else the initial.
pub fn states(
    bodies: &[RigidBody],
    mesh: &Mesh,
    u: &[f64],
    residual: &[f64],
    fext: &[f64],
    current: bool,
) -> Vec<RigidState> {
    bodies
        .iter()
        .map(|b| {
            let pos = |n: usize| {
                let x = mesh.coords[n];
                if current {
                    [x[0] + u[2 * n], x[1] + u[2 * n + 1]]
                } else {
                    x
                }
            };
            let r = pos(b.ref_node);
            let mut reaction = [0.0; 3];
            let mut nodes = b.nodes.clone();
            if !nodes.contains(&b.ref_node) {
                nodes.push(b.ref_node);
            }
            for n in nodes {
                let f = [
                    residual[2 * n] + fext[2 * n],
                    residual[2 * n + 1] + fext[2 * n + 1],
                ];
                let x = pos(n);
                reaction[0] += f[0];
                reaction[1] += f[1];
                reaction[2] += (x[0] - r[0]) * f[1] - (x[1] - r[1]) * f[0];
            }
            RigidState {
                name: b.name.clone(),
                motion: [u[2 * b.ref_node], u[2 * b.ref_node + 1], u[2 * b.rot_node]],
                reaction,
            }
        })
        .collect()
}
