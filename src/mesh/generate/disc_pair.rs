//! Two equal half discs touching at the origin: the upper one centred at (0, R), the lower
//! one its mirror image centred at (0, −R), graded as the SSNP154 cylinder. The lower disc's
//! nodes are turned about its centre by ε cos θ (θ their polar angle, ε = stretch − 1),
//! which keeps the axis and the circles and stretches its cells along the arc by `stretch`
//! at the contact: the two arcs match only for stretch = 1. In plane strain it is the Hertz
//! contact of two cylinders, in axisymmetry (x the radius) that of two spheres; the problem
//! is symmetric about y = 0.

use super::super::builder::MeshBuilder;
use super::super::Mesh;
use super::ssnp154::{half_disc, HalfDisc};
use crate::error::{Error, Result};

#[derive(Clone, Debug)]
pub struct DiscPairOptions {
    pub quadratic: bool,
    /// Radius of both discs.
    pub radius: f64,
    /// Element size at the contact (the upper disc's).
    pub size: f64,
    /// The lower disc's arc cells at the contact are this many times the upper disc's
    /// (in [0.5, 1.5]; 1: mirror images).
    pub stretch: f64,
}

/// The radius the half-disc mesher works in (the SSNP154 cylinder's); the mesh is scaled.
const BASE_RADIUS: f64 = 50.0;

/// Groups: Upper, Lower (cells); Upper_arc, Lower_arc (the quarter arcs facing each
/// other); Axe (edges on x = 0, both discs); points Upper_tip, Lower_tip (the two nodes at
/// the origin), Top (0, 2R) and Bottom (0, −2R).
pub fn disc_pair(o: &DiscPairOptions) -> Result<Mesh> {
    if !(o.radius.is_finite() && o.radius > 0.0) {
        return Err(Error::model(format!(
            "disc_pair mesh: radius must be positive and finite, got {}",
            o.radius
        )));
    }
    if !(0.5..=1.5).contains(&o.stretch) {
        return Err(Error::model(format!(
            "disc_pair mesh: stretch must lie in [0.5, 1.5], got {}",
            o.stretch
        )));
    }
    let scale = o.radius / BASE_RADIUS;
    let base = o.size / scale;
    if !(0.02..=6.0).contains(&base) {
        return Err(Error::model(format!(
            "disc_pair mesh: size must lie in [{}, {}] (0.0004 to 0.12 radius), got {}",
            0.02 * scale,
            6.0 * scale,
            o.size
        )));
    }
    let mut one = MeshBuilder::new("disc_pair generator");
    half_disc(
        &mut one,
        &HalfDisc {
            quadratic: o.quadratic,
            size: base,
            global_refine: 0,
            body: "Disc",
            arc: "Arc",
            contact_point: "Tip",
            far_point: "Far",
        },
    );
    let disc = one.finish()?;
    let mut b = MeshBuilder::new("disc_pair generator");
    let eps = o.stretch - 1.0;
    for lower in [false, true] {
        let mut m = disc.clone();
        for x in m.coords.iter_mut() {
            let (dx, dy) = (x[0], x[1] - BASE_RADIUS);
            let r = dx.hypot(dy);
            let mut p = *x;
            if lower && r > 0.0 {
                let th = dy.atan2(dx);
                let t = th + eps * th.cos();
                p = [r * t.cos(), BASE_RADIUS + r * t.sin()];
            }
            // nodes on the axis exactly at x = 0 (cos(−π/2) is 6e-17, not 0)
            if p[0].abs() < 1e-9 * BASE_RADIUS {
                p[0] = 0.0;
            }
            *x = [p[0] * scale, if lower { -p[1] } else { p[1] } * scale];
        }
        let side = if lower { "Lower" } else { "Upper" };
        b.append(&m, |g| match g {
            "Disc" => side.to_string(),
            "Arc" => format!("{side}_arc"),
            "Tip" => format!("{side}_tip"),
            "Far" if lower => "Bottom".to_string(),
            "Far" => "Top".to_string(),
            other => other.to_string(),
        });
    }
    let mut mesh = b.finish()?;
    // the mirrored cells were turned counter-clockwise by `finish`: that is the generator's
    // doing, not a property of the user's input
    mesh.reoriented = 0;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::super::area;
    use super::*;

    #[test]
    fn two_discs_mirror_each_other_with_their_own_sizes() {
        for quadratic in [false, true] {
            let m = disc_pair(&DiscPairOptions {
                quadratic,
                radius: 0.05,
                size: 0.001,
                stretch: 1.3,
            })
            .unwrap();
            let half = std::f64::consts::PI * 0.05 * 0.05 / 2.0;
            let tol = if quadratic { 1e-4 } else { 1e-2 };
            let rel = area(&m) / (2.0 * half) - 1.0;
            println!("quadratic {quadratic}: area {rel:+.2e} relative");
            assert!(rel.abs() < tol, "{}", area(&m));
            let (up, low) = (
                m.single_node("Upper_tip").unwrap(),
                m.single_node("Lower_tip").unwrap(),
            );
            assert_ne!(up, low);
            assert_eq!(m.coords[up], [0.0, 0.0]);
            assert_eq!(m.coords[low], [0.0, 0.0]);
            assert!((m.coords[m.single_node("Top").unwrap()][1] - 0.1).abs() < 1e-15);
            assert!((m.coords[m.single_node("Bottom").unwrap()][1] + 0.1).abs() < 1e-15);
            for (arc, sign) in [("Upper_arc", 1.0), ("Lower_arc", -1.0)] {
                for n in m.node_group(arc).unwrap() {
                    let x = m.coords[n];
                    assert!((x[0].hypot(x[1] - sign * 0.05) - 0.05).abs() < 1e-15);
                    if sign > 0.0 {
                        assert!(x[1] <= 0.05 + 1e-15, "the upper arc is the lower quarter");
                    }
                }
            }
            // different sizes: the arcs' nodes do not coincide away from the tip
            let upper: Vec<[f64; 2]> = m
                .node_group("Upper_arc")
                .unwrap()
                .iter()
                .map(|&n| m.coords[n])
                .collect();
            let matching = m
                .node_group("Lower_arc")
                .unwrap()
                .iter()
                .filter(|&&n| upper.iter().any(|u| (u[0] - m.coords[n][0]).abs() < 1e-9))
                .count();
            assert!(matching < 3, "{matching} lower arc nodes face an upper one");
            assert_eq!(m.reoriented, 0);
        }
    }

    #[test]
    fn bad_sizes_are_errors() {
        let o = DiscPairOptions {
            quadratic: false,
            radius: 50.0,
            size: 1.0,
            stretch: 2.0,
        };
        let e = disc_pair(&o).unwrap_err().to_string();
        assert!(e.contains("stretch"), "{e}");
        let e = disc_pair(&DiscPairOptions {
            size: 100.0,
            stretch: 1.0,
            ..o
        })
        .unwrap_err();
        assert!(e.to_string().contains("size"), "{e}");
        assert!(disc_pair(&DiscPairOptions { radius: -1.0, ..o }).is_err());
    }
}
