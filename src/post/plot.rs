//! Small dependency-free SVG line/point plots: linear or log axes, shaded x-bands, a legend
//! below the plot box (never over the data); the data ranges are written on the document so
//! that `read_back` recovers the data.
//!
//! Hand-written rather than `plotters`: the report's checks need what its SVG backend does
//! not write (the plot box and data ranges on the root element, one tagged element per
//! series, so that tests read the plotted points back and compare them with the CSV), and a
//! legend outside the plot box, which its series-label box does not offer; the whole module
//! is ~250 lines with no dependency.

use std::fmt::Write;

pub struct Series<'a> {
    pub label: &'a str,
    pub color: &'a str,
    pub points: &'a [(f64, f64)],
    pub style: Style,
}

/// How a series is drawn.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Line,
    Markers,
    /// Markers joined by a line (e.g. the iterations of one Newton step).
    LineMarkers,
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

/// Shaded x-ranges behind the curves (e.g. stick and slip zones), with a legend entry.
pub struct Band<'a> {
    pub label: &'a str,
    pub color: &'a str,
    pub ranges: Vec<(f64, f64)>,
}

#[derive(Default)]
pub struct Options<'a> {
    /// Logarithmic axes (values ≤ 0 are left out).
    pub log_x: bool,
    pub log_y: bool,
    pub bands: Vec<Band<'a>>,
    /// Do not force y = 0 into the range.
    pub free_y: bool,
}

/// An SVG document with axes, ticks, labels and a legend.
pub fn svg(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    svg_with(title, xlabel, ylabel, series, &Options::default())
}

/// The plot box of a document (pixels) and the data ranges it maps, written on the root
/// element as `data-box="l t w h"`, `data-x="x0 x1"`, `data-y="y0 y1"` (log10 values on a
/// log axis) so that a reader can turn the points back into data.
pub fn svg_with(title: &str, xlabel: &str, ylabel: &str, series: &[Series], o: &Options) -> String {
    // the legend: bands then series, in rows of two columns (one when a label is long)
    // under the x-axis label
    let legend: Vec<(&str, &str)> = o
        .bands
        .iter()
        .map(|b| (b.label, b.color))
        .chain(series.iter().map(|s| (s.label, s.color)))
        .collect();
    let columns = if legend.iter().all(|e| e.0.chars().count() <= LEGEND_CHARS) {
        2
    } else {
        1
    };
    let legend_rows = legend.len().div_ceil(columns);
    let (w, plot_h) = (760.0, 480.0);
    let h = plot_h + 18.0 * legend_rows as f64 + if legend_rows > 0 { 8.0 } else { 0.0 };
    let (l, r, t) = (80.0, 30.0, 40.0);
    // bottom margin of the plot box: tick labels and the x-axis label
    let b = 60.0 + (h - plot_h);
    let tx = |x: f64| if o.log_x { x.log10() } else { x };
    let ty = |y: f64| if o.log_y { y.log10() } else { y };
    let ok = |x: f64, y: f64| {
        x.is_finite() && y.is_finite() && (!o.log_x || x > 0.0) && (!o.log_y || y > 0.0)
    };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in series.iter().flat_map(|s| s.points.iter()) {
        if ok(x, y) {
            x0 = x0.min(tx(x));
            x1 = x1.max(tx(x));
            y0 = y0.min(ty(y));
            y1 = y1.max(ty(y));
        }
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 < 1e-12 {
        (x0, x1) = (x0 - 0.5, x1 + 0.5);
    }
    if y1 - y0 < 1e-12 {
        (y0, y1) = (y0 - 0.5, y1 + 0.5);
    }
    if !o.log_y && !o.free_y {
        y0 = y0.min(0.0);
    }
    let (sx, sy) = if o.log_x || o.log_y {
        (
            if o.log_x { 1.0 } else { tick_step(x1 - x0) },
            if o.log_y { 1.0 } else { tick_step(y1 - y0) },
        )
    } else {
        (tick_step(x1 - x0), tick_step(y1 - y0))
    };
    x0 = (x0 / sx).floor() * sx;
    x1 = (x1 / sx).ceil() * sx;
    y0 = (y0 / sy).floor() * sy;
    y1 = (y1 / sy).ceil() * sy;
    let px = |x: f64| l + (x - x0) / (x1 - x0) * (w - l - r);
    let py = |y: f64| h - b - (y - y0) / (y1 - y0) * (h - t - b);
    let label = |v: f64, log: bool| {
        if log {
            format!("1e{}", v.round() as i64)
        } else {
            fmt_tick(v)
        }
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="13" data-box="{l} {t} {} {}" data-x="{x0} {x1}" data-y="{y0} {y1}">"#,
        w - l - r,
        h - t - b
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" text-anchor="middle" font-size="16">{}</text>"#,
        w / 2.0,
        escape(title)
    );
    for band in &o.bands {
        for &(a, c) in &band.ranges {
            let (pa, pc) = (px(tx(a)).max(l), px(tx(c)).min(w - r));
            if pc > pa {
                let _ = writeln!(
                    s,
                    r#"<rect class="band" data-label="{}" x="{pa:.1}" y="{t}" width="{:.1}" height="{:.1}" fill="{}" fill-opacity="0.35"/>"#,
                    escape(band.label),
                    pc - pa,
                    h - t - b,
                    band.color
                );
            }
        }
    }
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
            label(x, o.log_x)
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
            label(y, o.log_y)
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
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        (l + w - r) / 2.0,
        h - b + 44.0,
        escape(xlabel)
    );
    let _ = writeln!(
        s,
        r#"<text x="18" y="{:.1}" text-anchor="middle" transform="rotate(-90 18 {:.1})">{}</text>"#,
        (t + h - b) / 2.0,
        (t + h - b) / 2.0,
        escape(ylabel)
    );
    for ser in series {
        let pts: Vec<String> = ser
            .points
            .iter()
            .filter(|p| ok(p.0, p.1))
            .map(|&(x, y)| format!("{:.3},{:.3}", px(tx(x)), py(ty(y))))
            .collect();
        if ser.style != Style::Line {
            let _ = writeln!(
                s,
                r#"<g fill="{}" class="series" data-label="{}">"#,
                ser.color,
                escape(ser.label)
            );
            if ser.style == Style::LineMarkers {
                let _ = writeln!(
                    s,
                    r#"<polyline fill="none" stroke="{}" stroke-width="1.5" points="{}"/>"#,
                    ser.color,
                    pts.join(" ")
                );
            }
            for p in &pts {
                let (a, c) = p.split_once(',').unwrap();
                let _ = writeln!(s, r#"<circle cx="{a}" cy="{c}" r="3"/>"#);
            }
            let _ = writeln!(s, "</g>");
        } else {
            let _ = writeln!(
                s,
                r#"<polyline class="series" data-label="{}" fill="none" stroke="{}" stroke-width="2" points="{}"/>"#,
                escape(ser.label),
                ser.color,
                pts.join(" ")
            );
        }
    }
    let _ = writeln!(s, r#"<g class="legend">"#);
    for (k, (text, color)) in legend.iter().enumerate() {
        let ly = plot_h + 8.0 + 18.0 * (k / columns) as f64;
        let lx = l + (k % columns) as f64 * (w - l - r) / columns as f64;
        let _ = writeln!(
            s,
            r#"<rect x="{lx}" y="{:.1}" width="14" height="6" fill="{color}"/>"#,
            ly - 7.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{ly:.1}">{}</text>"#,
            lx + 20.0,
            escape(text)
        );
    }
    s.push_str("</g>\n</svg>\n");
    s
}

/// Legend labels up to this many characters fit two to a row (13 px sans-serif).
const LEGEND_CHARS: usize = 40;

/// A number to `digits` significant digits, without an exponent for 1e-4 ≤ |v| < 1e6
/// (tables and captions: a rate is 1.52, not 1.5182325275954309).
pub fn sig(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return "-".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&mag) {
        return format!("{:.*e}", digits.saturating_sub(1), v);
    }
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    format!("{v:.decimals$}")
}

/// Text for XML content and attributes.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The data points of every series of a document made by `svg_with`, read back from the
/// pixel coordinates: (label, points). For tests and for checking a report.
pub fn read_back(doc: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    let attr = |tag: &str, key: &str| -> Option<String> {
        let at = tag.find(&format!(" {key}=\""))? + key.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_string())
    };
    let nums = |v: String| -> Vec<f64> {
        v.split_ascii_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect()
    };
    let root = &doc[..doc.find('>').unwrap_or(0)];
    let (bx, xr, yr) = (
        nums(attr(root, "data-box").unwrap_or_default()),
        nums(attr(root, "data-x").unwrap_or_default()),
        nums(attr(root, "data-y").unwrap_or_default()),
    );
    if bx.len() != 4 || xr.len() != 2 || yr.len() != 2 {
        return vec![];
    }
    let to_data = |px: f64, py: f64| {
        (
            xr[0] + (px - bx[0]) / bx[2] * (xr[1] - xr[0]),
            yr[0] + (bx[1] + bx[3] - py) / bx[3] * (yr[1] - yr[0]),
        )
    };
    let mut out = vec![];
    for (i, _) in doc.match_indices("class=\"series\"") {
        let tag_start = doc[..i].rfind('<').unwrap_or(0);
        let tag_end = i + doc[i..].find('>').unwrap_or(0);
        let tag = &doc[tag_start..tag_end];
        let label = attr(tag, "data-label").unwrap_or_default();
        let mut pts = vec![];
        if tag.starts_with("<polyline") {
            for p in attr(tag, "points")
                .unwrap_or_default()
                .split_ascii_whitespace()
            {
                if let Some((a, b)) = p.split_once(',') {
                    if let (Ok(a), Ok(b)) = (a.parse(), b.parse()) {
                        pts.push(to_data(a, b));
                    }
                }
            }
        } else {
            let group_end = tag_end + doc[tag_end..].find("</g>").unwrap_or(0);
            for c in doc[tag_end..group_end].split("<circle").skip(1) {
                let cx = attr(c, "cx").and_then(|v| v.parse().ok());
                let cy = attr(c, "cy").and_then(|v| v.parse().ok());
                if let (Some(a), Some(b)) = (cx, cy) {
                    pts.push(to_data(a, b));
                }
            }
        }
        out.push((label, pts));
    }
    out
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
                style: Style::Line,
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

    #[test]
    fn read_back_recovers_the_data_on_linear_and_log_axes() {
        let data = [(0.1, 3.0), (0.5, 0.02), (2.0, 1e-5)];
        for (log_x, log_y) in [(false, false), (true, true), (false, true)] {
            let o = Options {
                log_x,
                log_y,
                ..Default::default()
            };
            let s = [Series {
                label: "a<b",
                color: "red",
                points: &data,
                style: if log_y {
                    Style::LineMarkers
                } else {
                    Style::Line
                },
            }];
            let doc = svg_with("t", "x", "y", &s, &o);
            let back = read_back(&doc);
            assert_eq!(back.len(), 1);
            assert_eq!(back[0].0, "a&lt;b");
            for (&(x, y), &(bx, by)) in data.iter().zip(&back[0].1) {
                let (ex, ey) = (
                    if log_x { x.log10() } else { x },
                    if log_y { y.log10() } else { y },
                );
                // pixels are written to 1e-3 of 650 × 380: relative 1e-5 of the range
                assert!((bx - ex).abs() < 1e-4 * 3.0, "{bx} {ex}");
                assert!((by - ey).abs() < 1e-4 * 7.0, "{by} {ey}");
            }
        }
    }
}
