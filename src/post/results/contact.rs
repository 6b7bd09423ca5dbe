//! The per-pair contact outputs of results.json and history.csv, and the contact columns
//! of the curves.

use crate::post::contact_pressure::half_width;
use crate::post::contact_summary::{PairResult, PairSummary};
use serde_json::{json, Value};

/// The results.json entry of one pair. `axisymmetric` names the contact measure
/// `contact_area` (∫ 2πr ds) instead of `contact_length`.
pub fn pair_json(slave: &str, master: &str, s: &PairSummary, axisymmetric: bool) -> Value {
    let measure = if axisymmetric {
        "contact_area"
    } else {
        "contact_length"
    };
    let mut v = json!({
        "slave": slave,
        "master": master,
        "normal_resultant": s.normal_resultant,
        "tangential_resultant": s.tangential_resultant,
        "normal_force": s.normal_force,
        "tangential_force": s.tangential_force,
        "force": s.force,
        "centre_of_pressure": s.centre_of_pressure,
        "peak_pressure": s.peak_pressure,
        "peak_node": s.peak_node,
        "peak_at": s.peak_at,
        "stick": s.stick,
        "slip": s.slip,
        "open": s.open,
    });
    v[measure] = json!(s.contact_length);
    v
}

/// The Hertz line-contact fits of SSNP154-like cases (a contact zone symmetric about
/// x = 0, its half on x ≥ 0): the half-width of an elliptical fit to the nodal pressures,
/// and the largest |x| of a sticking loaded node. Only meaningful where a Hertz profile is
/// expected, so written only with [output.hertz].
pub fn hertz_fits(result: &PairResult, mu: f64, coords: &[[f64; 2]]) -> Value {
    let samples: Vec<(f64, f64)> = result
        .nodes
        .iter()
        .map(|c| (coords[c.node][0].abs(), c.pressure))
        .collect();
    let peak = samples.iter().fold(0.0f64, |m, p| m.max(p.1));
    // stick zone: loaded slave nodes whose shear is below μ p (|Λ| < 1)
    let stick = (mu > 0.0).then(|| {
        result
            .nodes
            .iter()
            .filter(|c| c.pressure > 1e-3 * peak && c.shear.abs() < mu * c.pressure * (1.0 - 1e-4))
            .map(|c| coords[c.node][0].abs())
            .fold(0.0f64, f64::max)
    });
    json!({"half_width": half_width(&samples), "stick_zone_extent": stick})
}

/// The history.csv columns of pair `i` (1-based).
pub fn csv_header(i: usize, axisymmetric: bool) -> String {
    let measure = if axisymmetric { "area" } else { "length" };
    [
        "normal",
        "tangential",
        "normal_fx",
        "normal_fy",
        "tangential_fx",
        "tangential_fy",
        measure,
        "xc",
        "yc",
        "peak",
        "peak_x",
        "peak_y",
        "stick",
        "slip",
        "open",
    ]
    .iter()
    .map(|q| format!(",contact{i}_{q}"))
    .collect()
}

/// The values of `csv_header`'s columns (empty where undefined: no load, no peak).
pub fn csv_values(s: &PairSummary) -> String {
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    let c = s.centre_of_pressure;
    let p = s.peak_at;
    format!(
        ",{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        s.normal_resultant,
        s.tangential_resultant,
        s.normal_force[0],
        s.normal_force[1],
        s.tangential_force[0],
        s.tangential_force[1],
        s.contact_length,
        opt(c.map(|c| c[0])),
        opt(c.map(|c| c[1])),
        s.peak_pressure,
        opt(p.map(|p| p[0])),
        opt(p.map(|p| p[1])),
        s.stick,
        s.slip,
        s.open
    )
}
