//! The rigid surfaces' reference points in the loading: each of their dofs imposed (and
//! the rotation's motion of the surface's nodes), driven by a force or a moment, or held.

use super::super::schema::CaseFile;
use super::{compile, lookup, time_expr, value_at, Forces};
use crate::error::{Error, Result};
use crate::fem::solid::Kinematics;
use crate::mesh::Mesh;
use crate::solver::history::{Imposed, Place, TimeFunction};
use std::collections::BTreeMap;

/// The reference points of the rigid surfaces: each dof imposed (an imposed value, and for
/// the rotation the motion it gives the surface's nodes, last), driven by a force or a
/// moment, or held at 0.
pub(super) fn rigid_motions(
    case: &CaseFile,
    mesh: &Mesh,
    funcs: &BTreeMap<String, TimeFunction>,
    fixed: &mut Vec<(usize, f64)>,
    imposed: &mut Vec<Imposed>,
    out: &mut Forces,
) -> Result<()> {
    let bodies = super::super::rigid::bodies(case, mesh)?;
    let mut follow = vec![];
    for (spec, b) in case.rigid.iter().zip(&bodies) {
        let what = &b.what;
        let function = lookup(funcs, &spec.function, what)?;
        let x = b.reference;
        let dofs = [
            (2 * b.ref_node, "dx", &spec.dx, "fx", &spec.fx),
            (2 * b.ref_node + 1, "dy", &spec.dy, "fy", &spec.fy),
            (
                2 * b.rot_node,
                "rotation",
                &spec.rotation,
                "moment",
                &spec.moment,
            ),
        ];
        for (d, key, motion, force_key, force) in dofs {
            match (motion, force) {
                (Some(_), Some(_)) => {
                    return Err(Error::model(format!(
                        "{what}: {key} and {force_key} both given: each dof of the reference \
                         point is either imposed ({key}) or driven by a load ({force_key}), \
                         not both"
                    )))
                }
                (Some(v), None) => {
                    let key_what = format!("{what}: {key}");
                    let value = compile(v, &key_what, &spec.function)?;
                    if value.uses_t() {
                        let source = time_expr(value, &key_what);
                        let at_1 = source.expr.eval(x, 1.0);
                        fixed.push((d, if at_1.is_finite() { at_1 } else { 0.0 }));
                        imposed.push(Imposed::Field {
                            dofs: vec![(d, x)],
                            source,
                        });
                    } else {
                        let v = value_at(&value, &key_what, x, Place::Node(d / 2))?;
                        fixed.push((d, v));
                        imposed.push(Imposed::Scaled {
                            dofs: vec![(d, v)],
                            function: function.clone(),
                        });
                    }
                }
                (None, Some(v)) => {
                    let key_what = format!("{what}: {force_key}");
                    let value = compile(v, &key_what, &spec.function)?;
                    let point = vec![(x, Place::Node(d / 2), vec![(d, 1.0)])];
                    out.add(value, &key_what, function.clone(), point)?;
                }
                (None, None) => fixed.push((d, 0.0)),
            }
        }
        if spec.moment.is_some() && case.model.kinematics == Kinematics::Large {
            return Err(Error::model(format!(
                "{what}: moment makes the rotation an unknown, which is linearised (small \
                 rotations): with kinematics = \"large\" impose the rotation instead (an \
                 imposed rotation is exact)"
            )));
        }
        if !b.rotation_free {
            follow.push(Imposed::Follow {
                nodes: b
                    .nodes
                    .iter()
                    .filter(|&&n| n != b.ref_node)
                    .map(|&n| (n, mesh.coords[n]))
                    .collect(),
                center: x,
                angle: 2 * b.rot_node,
            });
        }
    }
    // (after every entry: they read the imposed rotation)
    imposed.extend(follow);
    Ok(())
}
