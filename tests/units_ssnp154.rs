//! No units in defaults, on the SSNP154 set-ups: every row of the validation (A–F and the
//! node-to-segment variants) on the built-in meshes with no contact parameter given (rho,
//! rho_f from the model), in N-mm-MPa and in N-m-Pa (lengths × 1e-3, moduli × 1e6, the
//! forces in N on a thickness of 1 mm either way): DY_B and SIYY_B agree to 1e-6 relative.
//! Mortar on A–D too.

use tribo::case::{self, ssnp154};

/// (DY_B, SIYY_B) in mm and MPa, from a run in units where lengths are `l` (1 or 1e-3)
/// and stresses `s` (1 or 1e6).
fn answer(id: &str, formulation: Option<&str>, l: f64, s: f64) -> (f64, f64) {
    let quadratic = ssnp154::REFERENCES
        .iter()
        .find(|r| r.0 == &id[..1])
        .unwrap()
        .1;
    let mut c = ssnp154::contact_case(id, ssnp154::builtin_mesh(quadratic, 1.5), formulation);
    let mut mesh = case::build_mesh(&c.mesh, std::path::Path::new("")).unwrap();
    for x in &mut mesh.coords {
        *x = [x[0] * l, x[1] * l];
    }
    c.model.thickness *= l;
    for m in &mut c.material {
        m.young *= s;
    }
    for k in &mut c.contact {
        k.rho = None;
        k.rho_f = None;
        k.initial_gap = k.initial_gap.map(|g| g * l);
    }
    // forces in N on the thickness: 17 500 N either way (a stress × an area: s l²)
    for f in &mut c.force {
        f.fy = f.fy.take().map(|v| v * s * l * l);
    }
    let out = case::run(&c, &mesh, false).unwrap_or_else(|e| panic!("{id} ({l}, {s}): {e}"));
    let p = |n: &str| out.probes.iter().find(|q| q.0 == n).unwrap().1;
    (p("DY_B") / l, p("SIYY_B") / s)
}

#[test]
fn ssnp154_rows_give_the_same_answer_in_mm_mpa_and_m_pa_with_the_defaults() {
    let mut rows: Vec<(&str, Option<&str>)> = ssnp154::ROWS.iter().map(|r| (r.id, None)).collect();
    rows.extend(["A", "B", "C", "D"].map(|id| (id, Some("mortar"))));
    for (id, formulation) in rows {
        let mm = answer(id, formulation, 1.0, 1.0);
        let si = answer(id, formulation, 1e-3, 1e6);
        let d = (mm.0 / si.0 - 1.0).abs().max((mm.1 / si.1 - 1.0).abs());
        println!(
            "{id} {formulation:?}: DY_B {:.7} SIYY_B {:.3} (N-mm-MPa), relative difference {d:.1e}",
            mm.0, mm.1
        );
        assert!(d < 1e-6, "{id} {formulation:?}: {mm:?} vs {si:?}");
    }
}
