//! An SVG picture of the deformed contact region: the 2D cells inside a window around the
//! contact, drawn at their deformed positions (true scale) and filled by their mean nodal
//! von Mises stress, with the slave surface nodes marked by contact status.

use super::contact_state::{OPEN, SLIP, STICK};
use super::plot::escape;
use crate::mesh::Mesh;
use std::fmt::Write;

pub struct Picture<'a> {
    pub title: &'a str,
    pub mesh: &'a Mesh,
    pub u: &'a [f64],
    pub von_mises: &'a [f64],
    /// Window in the initial coordinates: [xmin, xmax] × [ymin, ymax].
    pub window: [[f64; 2]; 2],
    /// (node, status code) of the slave nodes.
    pub status: &'a [(usize, i32)],
}

/// A blue–green–yellow–red colour scale on t ∈ [0, 1].
pub fn color(t: f64) -> String {
    let stops = [
        (0.0, [48.0, 18.0, 159.0]),
        (0.25, [33.0, 145.0, 230.0]),
        (0.5, [55.0, 200.0, 120.0]),
        (0.75, [250.0, 200.0, 40.0]),
        (1.0, [200.0, 30.0, 30.0]),
    ];
    let t = t.clamp(0.0, 1.0);
    let k = stops.iter().rposition(|s| s.0 <= t).unwrap_or(0).min(3);
    let (a, b) = (stops[k], stops[k + 1]);
    let f = (t - a.0) / (b.0 - a.0);
    let c: Vec<u8> = (0..3)
        .map(|i| (a.1[i] + f * (b.1[i] - a.1[i])).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

pub fn svg(p: &Picture) -> String {
    let (w, h) = (760.0, 520.0);
    let (l, t, pw, ph) = (20.0, 40.0, 620.0, 460.0);
    let m = p.mesh;
    let pos = |n: usize| [m.coords[n][0] + p.u[2 * n], m.coords[n][1] + p.u[2 * n + 1]];
    let inside = |n: usize| {
        let x = m.coords[n];
        x[0] >= p.window[0][0]
            && x[0] <= p.window[0][1]
            && x[1] >= p.window[1][0]
            && x[1] <= p.window[1][1]
    };
    let cells: Vec<usize> = m
        .cells_of_dim(2)
        .filter(|&c| m.cell_nodes(c).iter().all(|&n| inside(n)))
        .collect();
    // Fit the deformed window into the box, same scale on both axes.
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for &c in &cells {
        for &n in m.cell_nodes(c) {
            let x = pos(n);
            for d in 0..2 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
    }
    if lo[0] > hi[0] {
        (lo, hi) = ([0.0; 2], [1.0; 2]);
    }
    let scale = (pw / (hi[0] - lo[0]).max(1e-12)).min(ph / (hi[1] - lo[1]).max(1e-12));
    let sx = |x: f64| l + (x - lo[0]) * scale;
    let sy = |y: f64| t + ph - (y - lo[1]) * scale;
    let vmax = cells
        .iter()
        .flat_map(|&c| m.cell_nodes(c).iter().map(|&n| p.von_mises[n]))
        .fold(0.0f64, f64::max)
        .max(1e-300);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="13">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="16">{}</text>"#,
        w / 2.0,
        escape(p.title)
    );
    for &c in &cells {
        let nodes = m.cell_nodes(c);
        let k = m.kind(c);
        // boundary of the cell: corner, mid-side, corner, ... (quadratic cells)
        let nc = k.num_corners();
        let mut ring = vec![];
        for i in 0..nc {
            ring.push(nodes[i]);
            if k.is_quadratic() {
                ring.push(nodes[nc + i]);
            }
        }
        let pts: Vec<String> = ring
            .iter()
            .map(|&n| {
                let x = pos(n);
                format!("{:.2},{:.2}", sx(x[0]), sy(x[1]))
            })
            .collect();
        let v = nodes.iter().map(|&n| p.von_mises[n]).sum::<f64>() / nodes.len() as f64;
        let _ = writeln!(
            s,
            r##"<polygon points="{}" fill="{}" stroke="#333" stroke-width="0.3"/>"##,
            pts.join(" "),
            color(v / vmax)
        );
    }
    for &(n, st) in p.status {
        if !inside(n) {
            continue;
        }
        let x = pos(n);
        let c = match st {
            OPEN => "#ffffff",
            STICK => "#2ca02c",
            SLIP => "#ff7f0e",
            _ => "#000000",
        };
        let _ = writeln!(
            s,
            r#"<circle cx="{:.2}" cy="{:.2}" r="3" fill="{c}" stroke="black" stroke-width="0.6"/>"#,
            sx(x[0]),
            sy(x[1])
        );
    }
    // colour bar and status legend
    let bx = l + pw + 30.0;
    for i in 0..50 {
        let f = i as f64 / 49.0;
        let _ = writeln!(
            s,
            r#"<rect x="{bx}" y="{:.1}" width="18" height="{:.2}" fill="{}"/>"#,
            t + 26.0 + (ph * 0.6 - 26.0) * (1.0 - f),
            (ph * 0.6 - 26.0) / 49.0 + 0.5,
            color(f)
        );
    }
    let _ = writeln!(
        s,
        // (the title in two lines: the 90 px right of the picture hold "von Mises" but
        // not "von Mises (MPa)")
        r#"<text x="{:.1}" y="{:.1}">{:.0}</text><text x="{:.1}" y="{:.1}">0</text><text x="{bx}" y="{:.1}">von Mises</text><text x="{bx}" y="{:.1}">(MPa)</text>"#,
        bx + 22.0,
        t + 10.0 + 26.0,
        vmax,
        bx + 22.0,
        t + ph * 0.6 + 4.0,
        t - 8.0,
        t + 8.0
    );
    for (k, (label, c)) in [
        ("open", "#ffffff"),
        ("stick / closed", "#2ca02c"),
        ("slip", "#ff7f0e"),
    ]
    .iter()
    .enumerate()
    {
        let y = t + ph * 0.7 + 20.0 * k as f64;
        let _ = writeln!(
            s,
            r#"<circle cx="{:.1}" cy="{y:.1}" r="4" fill="{c}" stroke="black"/><text x="{:.1}" y="{:.1}">{label}</text>"#,
            bx + 6.0,
            bx + 16.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{l}" y="{:.1}">deformed, true scale; {:.1} mm across</text>"#,
        h - 6.0,
        hi[0] - lo[0]
    );
    s.push_str("</svg>\n");
    s
}
