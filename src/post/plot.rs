//! Small dependency-free SVG line/point plots (pressure along the contact against Hertz).

use std::fmt::Write;

pub struct Series<'a> {
    pub label: &'a str,
    pub color: &'a str,
    pub points: &'a [(f64, f64)],
    /// Draw markers instead of a line.
    pub markers: bool,
}

/// A "nice" tick step for a range.
fn tick_step(span: f64) -> f64 {
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let n = raw / mag;
    let f = if n < 1.5 {
        1.0
    } else if n < 3.5 {
        2.0
    } else if n < 7.5 {
        5.0
    } else {
        10.0
    };
    f * mag
}

/// An SVG document with axes, ticks, labels and a legend.
pub fn svg(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    let (w, h) = (760.0, 480.0);
    let (l, r, t, b) = (80.0, 30.0, 40.0, 60.0);
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in all {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    y0 = y0.min(0.0);
    let (sx, sy) = (tick_step(x1 - x0), tick_step(y1 - y0));
    x0 = (x0 / sx).floor() * sx;
    x1 = (x1 / sx).ceil() * sx;
    y0 = (y0 / sy).floor() * sy;
    y1 = (y1 / sy).ceil() * sy;
    let px = |x: f64| l + (x - x0) / (x1 - x0) * (w - l - r);
    let py = |y: f64| h - b - (y - y0) / (y1 - y0) * (h - t - b);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="13">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="16">{title}</text>"#,
        w / 2.0
    );
    let mut x = x0;
    while x <= x1 + 1e-9 * sx {
        let p = px(x);
        let _ = writeln!(
            s,
            r##"<line x1="{p:.1}" y1="{t}" x2="{p:.1}" y2="{:.1}" stroke="#ddd"/>"##,
            h - b
        );
        let _ = writeln!(
            s,
            r#"<text x="{p:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            h - b + 18.0,
            fmt_tick(x)
        );
        x += sx;
    }
    let mut y = y0;
    while y <= y1 + 1e-9 * sy {
        let p = py(y);
        let _ = writeln!(
            s,
            r##"<line x1="{l}" y1="{p:.1}" x2="{:.1}" y2="{p:.1}" stroke="#ddd"/>"##,
            w - r
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            l - 6.0,
            p + 4.0,
            fmt_tick(y)
        );
        y += sy;
    }
    let _ = writeln!(
        s,
        r#"<rect x="{l}" y="{t}" width="{:.1}" height="{:.1}" fill="none" stroke="black"/>"#,
        w - l - r,
        h - t - b
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{xlabel}</text>"#,
        (l + w - r) / 2.0,
        h - 16.0
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{:.1}" text-anchor="middle" transform="rotate(-90 18 {:.1})">{ylabel}</text>"#,
        (t + h - b) / 2.0,
        (t + h - b) / 2.0
    );
    for (k, ser) in series.iter().enumerate() {
        let pts: Vec<String> = ser
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| format!("{:.2},{:.2}", px(x), py(y)))
            .collect();
        if ser.markers {
            let _ = writeln!(
                s,
                r#"<g fill="{}" class="series" data-label="{}">"#,
                ser.color, ser.label
            );
            for p in &pts {
                let (a, c) = p.split_once(',').unwrap();
                let _ = writeln!(s, r#"<circle cx="{a}" cy="{c}" r="3"/>"#);
            }
            let _ = writeln!(s, "</g>");
        } else {
            let _ = writeln!(
                s,
                r#"<polyline class="series" data-label="{}" fill="none" stroke="{}" stroke-width="2" points="{}"/>"#,
                ser.label,
                ser.color,
                pts.join(" ")
            );
        }
        let ly = t + 18.0 + 18.0 * k as f64;
        let lx = w - r - 200.0;
        let _ = writeln!(
            s,
            r#"<rect x="{lx}" y="{:.1}" width="14" height="4" fill="{}"/>"#,
            ly - 6.0,
            ser.color
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{ly:.1}">{}</text>"#,
            lx + 20.0,
            ser.label
        );
    }
    s.push_str("</svg>\n");
    s
}

fn fmt_tick(v: f64) -> String {
    let r = (v * 1e6).round() / 1e6;
    if r == r.trunc() {
        format!("{}", r as i64)
    } else {
        format!("{r}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polyline_holds_the_data_in_plot_coordinates() {
        let data = [(0.0, 0.0), (1.0, 2.0), (2.0, 1.0)];
        let doc = svg(
            "t",
            "x",
            "y",
            &[Series {
                label: "d",
                color: "red",
                points: &data,
                markers: false,
            }],
        );
        assert!(doc.starts_with("<svg"));
        let pts = doc
            .split("points=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        let xy: Vec<(f64, f64)> = pts
            .split(' ')
            .map(|p| {
                let (a, b) = p.split_once(',').unwrap();
                (a.parse().unwrap(), b.parse().unwrap())
            })
            .collect();
        assert_eq!(xy.len(), 3);
        // x increasing, and the highest data point is the smallest SVG y
        assert!(xy[0].0 < xy[1].0 && xy[1].0 < xy[2].0);
        assert!(xy[1].1 < xy[2].1 && xy[2].1 < xy[0].1);
    }
}
