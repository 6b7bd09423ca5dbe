//! The TOML case file, mirrored by serde structs. Unknown keys are errors that list the
//! valid ones (serde's `deny_unknown_fields`).

use crate::expr::Value;
use crate::fem::material::Modelisation;
use crate::fem::solid::Kinematics;
use serde::{Deserialize, Deserializer, Serialize};

/// A point or a table row: exactly two numbers (serde would drop a third silently).
fn two<E: serde::de::Error>(v: Vec<f64>) -> Result<[f64; 2], E> {
    match v[..] {
        [a, b] => Ok([a, b]),
        _ => Err(E::custom(format!(
            "expected exactly 2 numbers [x, y], got {}",
            v.len()
        ))),
    }
}

fn pair<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
    two(Vec::<f64>::deserialize(d)?)
}

fn opt_pair<'de, D: Deserializer<'de>>(d: D) -> Result<Option<[f64; 2]>, D::Error> {
    Option::<Vec<f64>>::deserialize(d)?.map(two).transpose()
}

fn pairs<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[f64; 2]>, D::Error> {
    Vec::<Vec<f64>>::deserialize(d)?
        .into_iter()
        .map(two)
        .collect()
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    /// Free text shown in reports.
    #[serde(default)]
    pub title: String,
    pub mesh: MeshSpec,
    #[serde(default)]
    pub model: ModelSpec,
    #[serde(default)]
    pub material: Vec<MaterialSpec>,
    /// Time functions that loads and imposed displacements refer to by name.
    #[serde(default)]
    pub function: Vec<FunctionSpec>,
    #[serde(default)]
    pub displacement: Vec<DisplacementSpec>,
    /// Rigid motions (rotation, translation) imposed on the nodes of a group.
    #[serde(default)]
    pub rotation: Vec<RotationSpec>,
    #[serde(default)]
    pub force: Vec<ForceSpec>,
    #[serde(default)]
    pub pressure: Vec<PressureSpec>,
    #[serde(default)]
    pub traction: Vec<TractionSpec>,
    #[serde(default)]
    pub relation: Vec<RelationSpec>,
    #[serde(default)]
    pub contact: Vec<ContactSpec>,
    /// Rigid surfaces (masters of contact pairs) moved by a reference point.
    #[serde(default)]
    pub rigid: Vec<RigidSpec>,
    #[serde(default)]
    pub solver: SolverSpec,
    #[serde(default)]
    pub output: OutputSpec,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// Mesh file (Gmsh .msh), relative to the case file.
    pub file: Option<String>,
    /// Built-in generator: "ssnp154", "disc_pair", "rectangle" or "ring".
    pub generator: Option<String>,
    /// ssnp154: quadratic cells (Quad8/Tri6).
    #[serde(default)]
    pub quadratic: bool,
    /// ssnp154: element size at the contact (mm); disc_pair: that of the upper disc.
    pub size: Option<f64>,
    /// disc_pair: the lower disc's arc cells at the contact over the upper disc's
    /// (default 1: mirror images).
    pub stretch: Option<f64>,
    /// disc_pair: radius of both discs.
    pub radius: Option<f64>,
    /// rectangle / ring: cell kind ("Quad4", "Quad8", "Tri3", "Tri6").
    pub cell: Option<String>,
    #[serde(default, deserialize_with = "opt_pair")]
    pub origin: Option<[f64; 2]>,
    pub width: Option<f64>,
    pub height: Option<f64>,
    pub nx: Option<usize>,
    pub ny: Option<usize>,
    #[serde(default)]
    pub distortion: f64,
    pub r_in: Option<f64>,
    pub r_out: Option<f64>,
    pub n_r: Option<usize>,
    pub n_theta: Option<usize>,
    pub angle: Option<f64>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    #[serde(default = "default_modelisation")]
    pub modelisation: Modelisation,
    #[serde(default = "default_kinematics")]
    pub kinematics: Kinematics,
    /// Thickness for plane stress / plane strain.
    #[serde(default = "one")]
    pub thickness: f64,
}

impl Default for ModelSpec {
    fn default() -> Self {
        ModelSpec {
            modelisation: default_modelisation(),
            kinematics: default_kinematics(),
            thickness: 1.0,
        }
    }
}

fn default_modelisation() -> Modelisation {
    Modelisation::PlaneStrain
}
fn default_kinematics() -> Kinematics {
    Kinematics::Small
}
fn one() -> f64 {
    1.0
}
fn zero() -> Value {
    Value::Number(0.0)
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A group of 2D cells; omitted: every 2D cell of the mesh (one material only).
    #[serde(default)]
    pub group: Option<String>,
    #[serde(rename = "E")]
    pub young: f64,
    pub nu: f64,
}

impl MaterialSpec {
    /// The cells of the material: those of its group (an error if the mesh has no such
    /// group), or every 2D cell when the group is omitted.
    pub fn cells(&self, mesh: &crate::mesh::Mesh) -> crate::error::Result<Vec<usize>> {
        match &self.group {
            Some(g) => Ok(mesh.cell_group(g)?.to_vec()),
            None => Ok(mesh.cells_of_dim(2).collect()),
        }
    }

    /// "group 'Ring'", or "the whole mesh", for messages.
    pub fn label(&self) -> String {
        match &self.group {
            Some(g) => format!("group '{g}'"),
            None => "the whole mesh (no group given)".into(),
        }
    }
}

/// A piecewise-linear function of time: `table = [[t0, v0], [t1, v1], ...]`, times
/// increasing strictly; constant before the first and after the last point.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FunctionSpec {
    pub name: String,
    #[serde(deserialize_with = "pairs")]
    pub table: Vec<[f64; 2]>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DisplacementSpec {
    pub group: String,
    /// A number or an expression of x, y (the node's initial position) and t.
    pub dx: Option<Value>,
    pub dy: Option<Value>,
    /// Time function scaling the values (default: f(t) = t); not with an expression of t,
    /// which gives the value at time t itself.
    pub function: Option<String>,
}

/// u = R(angle · f(t)) (X − center) + center + (dx, dy) · f(t) − X on every node of the
/// group: a rotation (degrees, counter-clockwise) and a translation.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RotationSpec {
    pub group: String,
    #[serde(deserialize_with = "pair")]
    pub center: [f64; 2],
    /// Degrees, counter-clockwise, at f = 1.
    pub angle: f64,
    #[serde(default)]
    pub dx: f64,
    #[serde(default)]
    pub dy: f64,
    pub function: Option<String>,
}

/// A rigid surface: an edge group of the mesh that bounds no 2D cell, or a line or a
/// circle given here, moved as a whole by its reference point (ux, uy, rotation). Each of
/// the three is imposed (`dx`, `dy`, `rotation`), driven by a force (`fx`, `fy`, `moment`:
/// the point's dof is then an unknown), or else held at 0.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RigidSpec {
    /// The name a [[contact]] master refers to (for `group`: the group's name by default).
    pub name: Option<String>,
    /// An edge group of the mesh (Seg2/Seg3 cells of no 2D cell).
    pub group: Option<String>,
    pub line: Option<LineSpec>,
    pub circle: Option<CircleSpec>,
    /// The reference point, or `reference_node`: a one-node group of no 2D cell.
    #[serde(default, deserialize_with = "opt_pair")]
    pub reference: Option<[f64; 2]>,
    pub reference_node: Option<String>,
    /// Imposed motion of the reference point (numbers or expressions of t).
    pub dx: Option<Value>,
    pub dy: Option<Value>,
    /// Radians, counter-clockwise.
    pub rotation: Option<Value>,
    /// Force and moment (counter-clockwise) on the reference point.
    pub fx: Option<Value>,
    pub fy: Option<Value>,
    pub moment: Option<Value>,
    /// Time function scaling every value (default: f(t) = t).
    pub function: Option<String>,
}

/// A straight rigid line through `point`; `normal` points out of the rigid body, toward
/// the bodies it touches.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LineSpec {
    #[serde(deserialize_with = "pair")]
    pub point: [f64; 2],
    #[serde(deserialize_with = "pair")]
    pub normal: [f64; 2],
}

/// A rigid disc (`inside = false`, the default: contact on its outside) or a rigid bore
/// (`inside = true`), as a polygon of `segments` chords (default: chords of a quarter of
/// the shortest slave cell, at least 360).
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    #[serde(deserialize_with = "pair")]
    pub center: [f64; 2],
    pub radius: f64,
    pub segments: Option<usize>,
    #[serde(default)]
    pub inside: bool,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ForceSpec {
    pub group: String,
    /// Force applied at each node of the group (at least one component).
    #[serde(default)]
    pub fx: Option<Value>,
    #[serde(default)]
    pub fy: Option<Value>,
    pub function: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSpec {
    pub group: String,
    /// A number or an expression of x, y (the integration point's initial position) and t.
    pub p: Value,
    pub function: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TractionSpec {
    pub group: String,
    #[serde(default)]
    pub tx: Option<Value>,
    #[serde(default)]
    pub ty: Option<Value>,
    pub function: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RelationSpec {
    #[serde(default)]
    pub name: String,
    pub terms: Vec<TermSpec>,
    /// A number or an expression of t.
    #[serde(default = "zero")]
    pub rhs: Value,
    /// Time function scaling the right-hand side (default: f(t) = t); not with an
    /// expression of t.
    pub function: Option<String>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TermSpec {
    /// A group holding exactly one node.
    pub group: String,
    /// "dx" or "dy".
    pub dof: String,
    pub coef: f64,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Equal load steps over (0, end_time]; a step also ends at each output time and at
    /// each time of a function's table.
    #[serde(default = "one_usize")]
    pub steps: usize,
    /// The end of the history (default: the last time of the function tables, or 1).
    pub end_time: Option<f64>,
    #[serde(default = "default_tol")]
    pub tolerance: f64,
    #[serde(default = "default_iter")]
    pub max_iterations: usize,
}

impl Default for SolverSpec {
    fn default() -> Self {
        SolverSpec {
            steps: 1,
            end_time: None,
            tolerance: default_tol(),
            max_iterations: default_iter(),
        }
    }
}

fn one_usize() -> usize {
    1
}
fn default_tol() -> f64 {
    1e-6
}
fn default_iter() -> usize {
    25
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Write `result.vtu` (and `steps/step_NNNN.vtu` with `steps/step.pvd`).
    #[serde(default = "yes")]
    pub vtu: bool,
    /// Per-step outputs: probes and reactions of every output time in results.json and
    /// history.csv, and with `vtu` one VTU file per output time.
    #[serde(default = "yes")]
    pub history: bool,
    /// Times of the per-step outputs; default: every step.
    pub times: Option<Vec<f64>>,
    #[serde(default)]
    pub probe: Vec<ProbeSpec>,
    /// Hertz line-contact curve drawn on the pressure plot: half-width a and peak p0.
    pub hertz: Option<HertzSpec>,
    /// Nodal fields along edge groups, ordered by arc length (curve_NAME.csv).
    #[serde(default)]
    pub curve: Vec<CurveSpec>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CurveSpec {
    pub name: String,
    /// An edge group forming one chain.
    pub group: String,
    /// Adds the polar stress components sirr, sitt, sirt about this point.
    #[serde(default, deserialize_with = "opt_pair")]
    pub center: Option<[f64; 2]>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct HertzSpec {
    pub a: f64,
    pub p0: f64,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            vtu: true,
            history: true,
            times: None,
            probe: vec![],
            hertz: None,
            curve: vec![],
        }
    }
}

fn yes() -> bool {
    true
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ProbeSpec {
    pub name: String,
    /// Node group; the probe is the mean over its nodes. Give this or `at`.
    #[serde(default)]
    pub group: Option<String>,
    /// A point (x, y): the probe is the value at the nearest node of a 2D cell (of
    /// `stress_group` when given).
    #[serde(default, deserialize_with = "opt_pair")]
    pub at: Option<[f64; 2]>,
    /// dx, dy; Cauchy stress sixx, siyy, sizz, sixy, vmis; second Piola–Kirchhoff stress
    /// pk2xx, pk2yy, pk2zz, pk2xy; polar components sirr, sitt, sirt (with `center`);
    /// contact_pressure, contact_shear, contact_gap, contact_status (slave nodes).
    pub field: String,
    /// For stress fields: average the extrapolated values over the cells of this group only.
    pub stress_group: Option<String>,
    /// The pole of the polar fields sirr, sitt, sirt.
    #[serde(default, deserialize_with = "opt_pair")]
    pub center: Option<[f64; 2]>,
}

#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Edge group of the slave surface (carries the multipliers).
    pub slave: String,
    /// Edge group of the master surface.
    pub master: String,
    /// "mortar" (the default: see the README on which to choose), "point-to-segment" (the
    /// reference code's continuous method) or "node-to-segment" (its discrete method).
    #[serde(default = "default_formulation")]
    pub formulation: String,
    /// point-to-segment: "gauss" (3 points per slave cell) or "nodal".
    #[serde(default = "default_integration")]
    pub integration: String,
    #[serde(default = "three")]
    pub gauss_points: usize,
    /// Augmentation coefficient (stress / length); default from the model: 1e-3 E_min / h
    /// (h the shortest slave cell), 100 on SSNP154's scale.
    #[serde(default)]
    pub rho: Option<f64>,
    /// Initial status: "all" points active, or the "closed" ones (gap <= 0); default
    /// "all" (point-to-segment, node-to-segment) or the touching nodes (mortar).
    #[serde(default)]
    pub initial: Option<String>,
    /// With initial = "closed": open gaps up to this distance count as closed at the start.
    #[serde(default)]
    pub initial_gap: Option<f64>,
    /// mortar: initial gaps and overlaps up to this distance are removed, strain-free
    /// (surfaces that fit but are discretised differently on the two sides).
    #[serde(default)]
    pub adjust: Option<f64>,
    /// Coulomb friction coefficient (0: frictionless).
    #[serde(default)]
    pub friction: f64,
    /// Friction augmentation coefficient (1 / length); default from the model: 60 / h.
    /// Raised at points of low pressure p so that μ p ρ_f is at least E / (10 h)
    /// (`contact::friction::balanced_rho_f`).
    #[serde(default)]
    pub rho_f: Option<f64>,
    /// Node groups excluded from friction only (e.g. a node on a symmetry axis).
    #[serde(default)]
    pub friction_exclude: Vec<String>,
    /// node-to-segment: penalty stiffness (force per length) instead of exact
    /// non-penetration by multipliers.
    #[serde(default)]
    pub penalty: Option<f64>,
    /// node-to-segment with friction: tangential penalty (stick stiffness, force per
    /// length): a sticking node's tangential force is −k_t × its elastic slip instead of
    /// exact stick. None: exact stick.
    #[serde(default)]
    pub tangential_penalty: Option<f64>,
    /// Node groups of slave nodes excluded from contact (no pressure there).
    #[serde(default)]
    pub exclude: Vec<String>,
    /// point-to-segment, node-to-segment: the master normal on straight cells, "smoothed"
    /// (interpolated between the vertices' averaged normals: continuous along a polygon
    /// standing for a curve; the default) or "segment" (each cell's own normal, as the
    /// reference code does by default).
    #[serde(default)]
    pub master_normal: Option<String>,
}

fn default_formulation() -> String {
    "mortar".into()
}
fn default_integration() -> String {
    "gauss".into()
}
fn three() -> usize {
    3
}
