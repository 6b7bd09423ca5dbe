//! The validation report: its plots are the computed data (SVG points read back against
//! the CSV written beside them), friction plots carry stick/slip zones, the page holds
//! every section.

use std::path::Path;
use tribo::case::{self, ssnp154};
use tribo::cli::report::{write, Check, Row};
use tribo::post::plot::read_back;

#[test]
fn report_plots_are_the_computed_data() {
    // SSNP154 C (friction) on a coarse built-in mesh: every kind of plot.
    let spec = ssnp154::builtin_mesh(false, 3.0);
    let mesh = case::build_mesh(&spec, Path::new("")).unwrap();
    let c = ssnp154::contact_case("C", spec, None);
    let out = case::run(&c, &mesh, false).unwrap();
    let dy = out.probes.iter().find(|p| p.0 == "DY_B").unwrap().1;
    // what the pressure plot must show as "multipliers": the solver's nodal pressures
    let mut expected: Vec<(f64, f64)> = out.contact_pressure[0]
        .iter()
        .map(|&(n, p)| (mesh.coords[n][0], p))
        .filter(|p| p.0 <= 1.6 * 6.2146)
        .collect();
    expected.sort_by(|a, b| a.0.total_cmp(&b.0));
    let row = Row {
        id: "C".into(),
        setup: "test".into(),
        mesh_name: "built-in".into(),
        case: c,
        mesh,
        outcome: out,
        checks: vec![Check {
            quantity: "DY_B",
            value: dy,
            reference: -1.3010796,
            rel_error: (dy / -1.3010796 - 1.0).abs(),
            tolerance: 0.05,
            pass: true,
        }],
        wall: 0.0,
    };
    let dir = std::env::temp_dir().join(format!("tribo-report-{}", std::process::id()));
    write(&dir, &[row], "built-in meshes", "settings").unwrap();
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    for needle in [
        "<table>",
        "C: contact pressure",
        "C: shear traction",
        "deformed contact region",
        "Newton convergence",
        "Versions and settings",
    ] {
        assert!(html.contains(needle), "report.html lacks '{needle}'");
    }
    assert!(!html.contains("NaN"), "a NaN reached the report");
    for plot in ["C_pressure", "C_shear", "C_newton"] {
        let svg = std::fs::read_to_string(dir.join(format!("{plot}.svg"))).unwrap();
        let csv = std::fs::read_to_string(dir.join(format!("{plot}.csv"))).unwrap();
        let series = read_back(&svg);
        assert!(!series.is_empty(), "{plot}: no series");
        for (label, pts) in &series {
            let rows: Vec<(f64, f64)> = csv_rows(&csv)
                .into_iter()
                .filter(|r| r.0 == *label)
                .map(|r| (r.1, r.2))
                .collect();
            assert_eq!(rows.len(), pts.len(), "{plot} '{label}': point counts");
            let log_y = plot == "C_newton";
            let (xs, ys): (Vec<f64>, Vec<f64>) = rows.iter().copied().unzip();
            let span = |v: &[f64]| {
                v.iter().copied().fold(f64::MIN, f64::max)
                    - v.iter().copied().fold(f64::MAX, f64::min)
            };
            let (sx, sy) = (
                span(&xs).max(1.0),
                if log_y { 20.0 } else { span(&ys).max(1.0) },
            );
            for (&(x, y), &(bx, by)) in rows.iter().zip(pts) {
                let y = if log_y { y.log10() } else { y };
                // pixels are written to 1e-3: the data come back to ~1e-5 of the range
                assert!(
                    (bx - x).abs() < 2e-4 * sx,
                    "{plot} '{label}': x {bx} vs {x}"
                );
                assert!(
                    (by - y).abs() < 2e-4 * sy,
                    "{plot} '{label}': y {by} vs {y}"
                );
            }
        }
    }
    let csv = std::fs::read_to_string(dir.join("C_pressure.csv")).unwrap();
    let plotted: Vec<(f64, f64)> = csv_rows(&csv)
        .into_iter()
        .filter(|r| r.0 == "multipliers")
        .map(|r| (r.1, r.2))
        .collect();
    // a label with a comma is one quoted field
    assert!(csv_rows(&csv)
        .iter()
        .any(|r| r.0 == "stresses, slave (-n.sigma.n)"));
    // the Newton plot joins the iterations of each load step by a line
    let newton = std::fs::read_to_string(dir.join("C_newton.svg")).unwrap();
    let steps = newton.matches("class=\"series\"").count();
    assert!(steps >= 2, "{steps} load steps");
    assert_eq!(newton.matches("<polyline").count(), steps);
    // the legend lies below the plot box: no entry over the data
    for plot in ["C_pressure", "C_shear", "C_newton"] {
        let svg = std::fs::read_to_string(dir.join(format!("{plot}.svg"))).unwrap();
        let root = &svg[..svg.find('>').unwrap()];
        let bx: Vec<f64> = root
            .split("data-box=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .split(' ')
            .map(|v| v.parse().unwrap())
            .collect();
        let bottom = bx[1] + bx[3];
        let legend = &svg[svg.find("<g class=\"legend\">").unwrap()..];
        for y in legend.split(" y=\"").skip(1) {
            let y: f64 = y.split('"').next().unwrap().parse().unwrap();
            assert!(
                y > bottom + 20.0,
                "{plot}: legend at y = {y}, plot box to {bottom}"
            );
        }
    }
    // numbers in the page are rounded (no 0.7582325275954309)
    let mut text = String::new();
    for piece in html.split('<') {
        text.push_str(piece.split_once('>').map_or(piece, |p| p.1));
        text.push(' ');
    }
    let long = text
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .find(|w| w.split_once('.').is_some_and(|(_, d)| d.len() >= 7));
    assert_eq!(long, None, "an unrounded number in the text of report.html");
    assert_eq!(
        plotted, expected,
        "the CSV holds the solver's multiplier pressures"
    );
    let shear = std::fs::read_to_string(dir.join("C_shear.svg")).unwrap();
    assert!(
        shear.contains("class=\"band\" data-label=\"stick\""),
        "no stick zone drawn"
    );
    assert!(
        shear.contains("class=\"band\" data-label=\"slip\""),
        "no slip zone drawn"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// (series, x, y) rows of a plot's CSV, read by an RFC 4180 reader.
fn csv_rows(text: &str) -> Vec<(String, f64, f64)> {
    csv::Reader::from_reader(text.as_bytes())
        .records()
        .map(|r| {
            let r = r.unwrap();
            (
                r[0].to_string(),
                r[1].parse().unwrap(),
                r[2].parse().unwrap(),
            )
        })
        .collect()
}
