//! The SSNP154 benchmark (NAFEMS contact benchmark 1) as built-in cases, with the
//! reference values of its six modelisations (shared/ssnp154/reference.toml).

use super::schema::*;
use crate::fem::material::Modelisation;
use crate::fem::solid::Kinematics;

/// Reference values: (id, quadratic, DY_B, SIYY_B).
pub const REFERENCES: [(&str, bool, f64, f64); 6] = [
    ("A", false, -1.3069040401077, -3800.4949548283),
    ("B", true, -1.3080192481252, -3513.3741602327),
    ("C", false, -1.3010795638714, -3670.2561088662),
    ("D", true, -1.3026356448389, -3542.6878770218),
    ("E", false, -1.3067596639633, -3814.1811065942),
    ("F", true, -1.3080923611548, -3502.7937782466),
];

/// Hertz line contact of SSNP154 (small-strain half-spaces): half-width a (mm), peak p0
/// (MPa).
pub const HERTZ_A: f64 = 6.2146;
pub const HERTZ_P0: f64 = 3585.36;

/// The benchmark's bodies, supports and load, with B and C glued in y (DY(B) = DY(C))
/// instead of contact: the elastic stage that runs before contact exists.
pub fn glued_case(mesh: MeshSpec, kinematics: Kinematics) -> CaseFile {
    CaseFile {
        title: "SSNP154 geometry, bodies glued at B-C (no contact)".into(),
        mesh,
        model: ModelSpec {
            modelisation: Modelisation::PlaneStrain,
            kinematics,
            thickness: 1.0,
        },
        material: vec![
            MaterialSpec {
                group: Some("Block".into()),
                young: 70000.0,
                nu: 0.3,
            },
            MaterialSpec {
                group: Some("Cylinder".into()),
                young: 210000.0,
                nu: 0.3,
            },
        ],
        function: vec![],
        rotation: vec![],
        displacement: vec![
            DisplacementSpec {
                group: "Encast".into(),
                dx: Some(0.0.into()),
                dy: Some(0.0.into()),
                function: None,
            },
            DisplacementSpec {
                group: "Axe".into(),
                dx: Some(0.0.into()),
                dy: None,
                function: None,
            },
        ],
        force: vec![ForceSpec {
            group: "Force".into(),
            fx: None,
            fy: Some((-17500.0).into()),
            function: None,
        }],
        pressure: vec![],
        traction: vec![],
        contact: vec![],
        rigid: vec![],
        relation: vec![RelationSpec {
            name: "DY(B) = DY(C)".into(),
            terms: vec![
                TermSpec {
                    group: "B".into(),
                    dof: "dy".into(),
                    coef: 1.0,
                },
                TermSpec {
                    group: "C".into(),
                    dof: "dy".into(),
                    coef: -1.0,
                },
            ],
            rhs: 0.0.into(),
            function: None,
        }],
        solver: SolverSpec {
            steps: 2,
            ..Default::default()
        },
        output: OutputSpec {
            // validate, study and the benches write no VTU (nor keep per-step states)
            vtu: false,
            history: false,
            times: None,
            hertz: Some(HertzSpec {
                a: HERTZ_A,
                p0: HERTZ_P0,
            }),
            curve: vec![],
            probe: vec![
                ProbeSpec {
                    name: "DY_B".into(),
                    group: Some("B".into()),
                    at: None,
                    field: "dy".into(),
                    stress_group: None,
                    center: None,
                },
                ProbeSpec {
                    name: "SIYY_B".into(),
                    group: Some("B".into()),
                    at: None,
                    field: "siyy".into(),
                    stress_group: Some("Block".into()),
                    center: None,
                },
            ],
        },
    }
}

/// One row of the validation: a set-up, the modelisation whose reference it is checked
/// against, and the tolerances (relative) on DY_B and SIYY_B, or None for the run's default.
pub struct Row {
    pub id: &'static str,
    pub reference: &'static str,
    pub what: &'static str,
    pub tolerance: (Option<f64>, Option<f64>),
}

/// The six modelisations as the reference ran them, then what the reference could not run:
/// node-to-segment without its workarounds (no B–C tie, C not excluded) and with friction
/// on the quadratic mesh.
pub const ROWS: [Row; 9] = [
    row("A", "A", "as the reference"),
    row("B", "B", "as the reference"),
    row("C", "C", "as the reference"),
    row("D", "D", "as the reference"),
    row("E", "E", "as the reference: tie DY(B) = DY(C), C excluded"),
    row("F", "F", "as the reference: tie DY(B) = DY(C), C excluded"),
    row(
        "E-free",
        "E",
        "node-to-segment without the tie, C in contact",
    ),
    row(
        "F-free",
        "F",
        "node-to-segment without the tie, C in contact",
    ),
    Row {
        id: "D-nts",
        reference: "D",
        what: "node-to-segment with friction on the quadratic mesh",
        tolerance: (Some(2e-3), Some(1e-2)),
    },
];

const fn row(id: &'static str, reference: &'static str, what: &'static str) -> Row {
    Row {
        id,
        reference,
        what,
        tolerance: (None, None),
    }
}

/// Whether a row uses friction, and whether it is a node-to-segment set-up.
pub fn row_kind(id: &str) -> (bool, bool) {
    let friction = matches!(id, "C" | "D" | "D-nts");
    let node_to_segment = matches!(id, "E" | "F" | "E-free" | "F-free" | "D-nts");
    (friction, node_to_segment)
}

/// The reference set-up of a modelisation: large kinematics, contact between the
/// cylinder's arc (slave) and the block's top (master), 2 load steps, Newton tolerance
/// 1e-6. A and B: point-to-segment, 3 Gauss points, ρ = 100; the reference started with
/// every point active, we start with the points within 0.1 mm (about the contact zone of the
/// first load step): the same converged state in half the Newton iterations.
///
/// E and F (node-to-segment) as the reference: the B–C tie and C excluded from contact;
/// `E-free`/`F-free` without either; `D-nts` the D set-up with node-to-segment.
pub fn contact_case(id: &str, mesh: MeshSpec, formulation: Option<&str>) -> CaseFile {
    let mut c = glued_case(mesh, Kinematics::Large);
    c.title = format!("SSNP154 {id}: cylinder on block, Hertz contact");
    let (friction, nts) = row_kind(id);
    let tied = matches!(id, "E" | "F");
    if !tied {
        c.relation.clear();
    }
    c.solver.max_iterations = 50;
    let formulation = formulation.unwrap_or(if nts {
        "node-to-segment"
    } else {
        "point-to-segment"
    });
    // Mortar multipliers live on the block's top (the coarser surface): with the finer
    // cylinder arc as slave, its nodes must follow the kinks of the coarse block surface and
    // the pressure oscillates (26 % of p0 on the linear reference mesh, against 3 % here).
    let (slave, master) = if formulation == "mortar" {
        ("Top_B", "Bottom_C")
    } else {
        ("Bottom_C", "Top_B")
    };
    c.contact.push(ContactSpec {
        slave: slave.into(),
        master: master.into(),
        formulation: formulation.into(),
        integration: "gauss".into(),
        gauss_points: 3,
        // the reference's augmentation (mortar has none)
        rho: (formulation != "mortar").then_some(100.0),
        initial: Some("closed".into()),
        initial_gap: Some(0.1),
        adjust: None,
        friction: 0.0,
        rho_f: None,
        friction_exclude: vec![],
        penalty: None,
        tangential_penalty: None,
        exclude: if tied { vec!["C".into()] } else { vec![] },
        // the reference's own cell normals on the cylinder's polygon (no smoothing)
        master_normal: (formulation != "mortar").then(|| "segment".into()),
    });
    if friction {
        // Coulomb 0.1, nodal integration (trapezoid / Simpson), C excluded from friction only
        // (its slip is zero: DX = 0). The reference started from the touching points
        // (INTERPENETRE); the points within 0.1 mm give the same state in fewer iterations.
        let k = c.contact.last_mut().unwrap();
        k.friction = 0.1;
        if k.formulation != "mortar" {
            k.integration = "nodal".into();
            k.rho_f = Some(100.0);
        }
        k.friction_exclude = vec!["C".into()];
    }
    c
}

/// Mesh spec of the built-in SSNP154 mesh.
pub fn builtin_mesh(quadratic: bool, size: f64) -> MeshSpec {
    MeshSpec {
        file: None,
        generator: Some("ssnp154".into()),
        quadratic,
        size: Some(size),
        stretch: None,
        radius: None,
        cell: None,
        origin: None,
        width: None,
        height: None,
        nx: None,
        ny: None,
        distortion: 0.0,
        r_in: None,
        r_out: None,
        n_r: None,
        n_theta: None,
        angle: None,
    }
}
