//! Probes: the nodes a probe reads (its group, or the node nearest to its point), the
//! field it reads, and its value in a state: the mean of the field over its nodes.
//!
//! Fields: displacements (dx, dy); Cauchy stress (sixx, siyy, sizz, sixy; vmis); second
//! Piola–Kirchhoff stress (pk2xx, pk2yy, pk2zz, pk2xy: S = J F⁻¹ σ F⁻ᵀ, equal to the
//! Cauchy stress in small kinematics); polar components about a centre (sirr, sitt, sirt);
//! the contact values of a slave node (contact_pressure, contact_shear, contact_gap,
//! contact_status).

use super::contact_summary::PairResult;
use super::stress::{nodal_stresses, CellNodeStresses};
use crate::assembly::Assembler;
use crate::error::{Error, Result};
use crate::mesh::Mesh;

/// How far from the mesh a probe point may be, in mesh sizes (the bounding box's
/// diagonal): farther, every node is about as near as any other in floating point.
const MAX_PROBE_DISTANCE: f64 = 1e6;

pub const FIELDS: &str = "dx, dy, sixx, siyy, sizz, sixy, vmis, pk2xx, pk2yy, pk2zz, pk2xy, \
                          sirr, sitt, sirt, contact_pressure, contact_shear, contact_gap, \
                          contact_status";

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactField {
    Pressure,
    Shear,
    Gap,
    Status,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Field {
    /// Displacement component 0 (x) or 1 (y).
    Displacement(usize),
    /// Cauchy stress component [xx, yy, zz, xy].
    Cauchy(usize),
    VonMises,
    /// Second Piola–Kirchhoff stress component [xx, yy, zz, xy].
    Pk2(usize),
    /// Polar component [rr, θθ, rθ] of the Cauchy stress about `centre`.
    Polar(usize, [f64; 2]),
    Contact(ContactField),
}

impl Field {
    /// The field named `name`; `centre` is required by the polar fields and refused by the
    /// others. `what` names the probe in errors.
    pub fn parse(name: &str, centre: Option<[f64; 2]>, what: &str) -> Result<Field> {
        let f = match name {
            "dx" => Field::Displacement(0),
            "dy" => Field::Displacement(1),
            "sixx" => Field::Cauchy(0),
            "siyy" => Field::Cauchy(1),
            "sizz" => Field::Cauchy(2),
            "sixy" => Field::Cauchy(3),
            "vmis" => Field::VonMises,
            "pk2xx" => Field::Pk2(0),
            "pk2yy" => Field::Pk2(1),
            "pk2zz" => Field::Pk2(2),
            "pk2xy" => Field::Pk2(3),
            "sirr" | "sitt" | "sirt" => {
                let k = ["sirr", "sitt", "sirt"].iter().position(|&n| n == name);
                let c = centre.ok_or_else(|| {
                    Error::model(format!(
                        "{what}: field '{name}' (a polar component) needs center = [x, y], \
                         the pole of the polar frame"
                    ))
                })?;
                return Ok(Field::Polar(k.unwrap_or(0), c));
            }
            "contact_pressure" => Field::Contact(ContactField::Pressure),
            "contact_shear" => Field::Contact(ContactField::Shear),
            "contact_gap" => Field::Contact(ContactField::Gap),
            "contact_status" => Field::Contact(ContactField::Status),
            other => {
                return Err(Error::model(format!(
                    "{what}: field '{other}' is not one of {FIELDS}"
                )))
            }
        };
        if centre.is_some() {
            return Err(Error::model(format!(
                "{what}: center is for the polar fields sirr, sitt, sirt only, not '{name}'"
            )));
        }
        Ok(f)
    }
}

/// The polar components [rr, θθ, rθ] of the stress `s` ([xx, yy, zz, xy]) at the point
/// `x`, about `centre` (θ measured from the x axis; at the centre itself, θ = 0).
pub fn polar(s: &[f64; 4], x: [f64; 2], centre: [f64; 2]) -> [f64; 3] {
    let (dx, dy) = (x[0] - centre[0], x[1] - centre[1]);
    let r = dx.hypot(dy);
    let (c, sn) = if r > 0.0 {
        (dx / r, dy / r)
    } else {
        (1.0, 0.0)
    };
    let (sxx, syy, sxy) = (s[0], s[1], s[3]);
    [
        c * c * sxx + sn * sn * syy + 2.0 * c * sn * sxy,
        sn * sn * sxx + c * c * syy - 2.0 * c * sn * sxy,
        (syy - sxx) * c * sn + (c * c - sn * sn) * sxy,
    ]
}

/// A probe ready to read states.
#[derive(Clone, Debug)]
pub struct Probe {
    pub name: String,
    pub nodes: Vec<usize>,
    pub field: Field,
    /// Stresses averaged over the cells of this group only.
    pub stress_group: Option<String>,
}

/// Where a probe reads and what.
pub struct ProbeInput<'a> {
    pub name: &'a str,
    pub group: Option<&'a str>,
    pub at: Option<[f64; 2]>,
    pub field: &'a str,
    pub stress_group: Option<&'a str>,
    pub centre: Option<[f64; 2]>,
}

impl Probe {
    /// Checks the input against the mesh; errors name the probe.
    pub fn new(mesh: &Mesh, p: &ProbeInput) -> Result<Probe> {
        let what = format!("probe '{}'", p.name);
        let field = Field::parse(p.field, p.centre, &what)?;
        if let Some(g) = p.stress_group {
            mesh.cell_group(g)
                .map_err(|e| Error::model(format!("{what}: {e}")))?;
        }
        Ok(Probe {
            name: p.name.to_string(),
            nodes: probe_nodes(mesh, p, &what)?,
            field,
            stress_group: p.stress_group.map(str::to_string),
        })
    }

    /// The nodes off every slave surface, for a contact field (their values do not exist).
    pub fn off_surface(&self, slave_nodes: &[&[usize]]) -> Option<usize> {
        if !matches!(self.field, Field::Contact(_)) {
            return None;
        }
        self.nodes
            .iter()
            .copied()
            .find(|n| !slave_nodes.iter().any(|s| s.binary_search(n).is_ok()))
    }
}

/// The nodes a probe averages over: its group's, or the node nearest to its point.
fn probe_nodes(mesh: &Mesh, p: &ProbeInput, what: &str) -> Result<Vec<usize>> {
    match (p.group, p.at) {
        (Some(g), None) => mesh
            .node_group(g)
            .map_err(|e| Error::model(format!("{what}: {e}"))),
        (None, Some(at)) => {
            let (lo, hi) = crate::mesh::quality::bounding_box(mesh);
            let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
            let out = |k: usize| (lo[k] - at[k]).max(at[k] - hi[k]).max(0.0);
            if out(0).hypot(out(1)) > MAX_PROBE_DISTANCE * size {
                return Err(Error::model(format!(
                    "{what}: at = [{:e}, {:e}] is more than {MAX_PROBE_DISTANCE:e} times the mesh \
                     size ({size:.3e}) away from the mesh: no node is nearer than another there",
                    at[0], at[1]
                )));
            }
            let cells: Vec<usize> = match p.stress_group {
                Some(g) => mesh
                    .cell_group(g)
                    .map_err(|e| Error::model(format!("{what}: {e}")))?
                    .to_vec(),
                None => mesh.cells_of_dim(2).collect(),
            };
            let nearest = cells
                .iter()
                .flat_map(|&c| mesh.cell_nodes(c).iter().copied())
                .min_by(|&a, &b| {
                    let d = |n: usize| (mesh.coords[n][0] - at[0]).hypot(mesh.coords[n][1] - at[1]);
                    d(a).total_cmp(&d(b))
                })
                .ok_or_else(|| Error::model(format!("{what}: no node to probe")))?;
            Ok(vec![nearest])
        }
        _ => Err(Error::model(format!(
            "{what}: give either group = \"NAME\" or at = [x, y]"
        ))),
    }
}

/// The fields of one state that probes read.
pub struct StateFields<'a> {
    pub mesh: &'a Mesh,
    pub asm: &'a Assembler,
    pub u: &'a [f64],
    /// Cell-node Cauchy stresses and their average over every cell.
    pub elno: &'a CellNodeStresses,
    pub stress: &'a [[f64; 4]],
    /// The same for the second Piola–Kirchhoff stress (None: small kinematics, S = σ).
    pub pk2: Option<(&'a CellNodeStresses, &'a [[f64; 4]])>,
    /// Positions of the polar frames: deformed (large kinematics) or initial.
    pub deformed: bool,
    pub contact: &'a [PairResult],
}

impl Probe {
    /// The mean of the field over the probe's nodes.
    pub fn value(&self, st: &StateFields) -> Result<f64> {
        let what = format!("probe '{}'", self.name);
        let stresses = |pk2: bool| -> Result<Vec<[f64; 4]>> {
            let (elno, all) = match (pk2, st.pk2) {
                (true, Some(p)) => p,
                _ => (st.elno, st.stress),
            };
            Ok(match &self.stress_group {
                Some(g) => nodal_stresses(st.mesh, st.asm, elno, Some(g))
                    .map_err(|e| Error::model(format!("{what}: {e}")))?,
                None => all.to_vec(),
            })
        };
        let pos = |n: usize| {
            let x = st.mesh.coords[n];
            if st.deformed {
                [x[0] + st.u[2 * n], x[1] + st.u[2 * n + 1]]
            } else {
                x
            }
        };
        let values: Vec<f64> = match self.field {
            Field::Displacement(c) => self.nodes.iter().map(|&n| st.u[2 * n + c]).collect(),
            Field::Cauchy(k) | Field::Pk2(k) => {
                let s = stresses(matches!(self.field, Field::Pk2(_)))?;
                self.nodes.iter().map(|&n| s[n][k]).collect()
            }
            Field::VonMises => {
                let s = stresses(false)?;
                let vm = |n: usize| crate::fem::material::von_mises(&s[n]);
                self.nodes.iter().map(|&n| vm(n)).collect()
            }
            Field::Polar(k, c) => {
                let s = stresses(false)?;
                let p = |n: usize| polar(&s[n], pos(n), c)[k];
                self.nodes.iter().map(|&n| p(n)).collect()
            }
            Field::Contact(f) => {
                let mut out = vec![];
                for &n in &self.nodes {
                    let c = st
                        .contact
                        .iter()
                        .find_map(|p| p.nodes.iter().find(|c| c.node == n))
                        .ok_or_else(|| {
                            Error::model(format!(
                                "{what}: node {} is on no slave surface: it has no contact values",
                                n + 1
                            ))
                        })?;
                    out.push(match f {
                        ContactField::Pressure => c.pressure,
                        ContactField::Shear => c.shear,
                        ContactField::Gap => c.gap,
                        ContactField::Status => c.status as f64,
                    });
                }
                out
            }
        };
        if values.iter().any(|v| v.is_nan()) {
            return Err(Error::model(format!(
                "{what}: some of its nodes are in no cell of the stress group '{}'",
                self.stress_group.as_deref().unwrap_or("")
            )));
        }
        Ok(values.iter().sum::<f64>() / values.len() as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polar_components_turn_with_the_frame() {
        // σ_rr = 1, σ_θθ = 2, σ_rθ = 0.5 at θ = 30°: the Cartesian tensor back to polar
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (rr, tt, rt) = (1.0, 2.0, 0.5);
        let sxx = c * c * rr + s * s * tt - 2.0 * c * s * rt;
        let syy = s * s * rr + c * c * tt + 2.0 * c * s * rt;
        let sxy = c * s * (rr - tt) + (c * c - s * s) * rt;
        let p = polar(
            &[sxx, syy, 0.0, sxy],
            [1.0 + 2.0 * c, -1.0 + 2.0 * s],
            [1.0, -1.0],
        );
        for (a, b) in p.iter().zip([rr, tt, rt]) {
            assert!((a - b).abs() < 1e-14, "{p:?}");
        }
    }

    #[test]
    fn bad_fields_name_the_probe() {
        let e = Field::parse("sirr", None, "probe 'p'").unwrap_err();
        assert!(e.to_string().contains("probe 'p': field 'sirr'"), "{e}");
        assert!(e.to_string().contains("needs center"), "{e}");
        let e = Field::parse("sxx", None, "probe 'q'").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("probe 'q': field 'sxx' is not one of"),
            "{e}"
        );
        let e = Field::parse("dx", Some([0.0, 0.0]), "probe 'r'").unwrap_err();
        assert!(
            e.to_string().contains("center is for the polar fields"),
            "{e}"
        );
    }
}
