//! Slave nodes of zero weight: in axisymmetry a node on the axis whose share of the surface,
//! ∫ N_j dA with dA = 2πr ds, vanishes (a Seg3 corner; a node-to-segment node under the
//! trapezoid rule). Its multiplier carries no force and says nothing of the pressure there;
//! the pressure reported is the limit of its neighbourhood's. So is that of every node on
//! the axis, whatever the formulation gives it (a multiplier over a vanishing area).

/// Which of the nodes at `x` lie on the axis x = 0 (axisymmetric models only): within 1e-9
/// of the surface's extent.
pub fn on_axis(x: &[[f64; 2]], axisymmetric: bool) -> Vec<bool> {
    let extent = x
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .map(|p| axisymmetric && p[0].abs() <= 1e-9 * extent)
        .collect()
}

/// Replaces the pressure of each weightless node by the value at it of p = α + β d² (an
/// axisymmetric field is even in the distance d from the axis) through the two nearest
/// weighted nodes of the surface (`x`: the nodes' positions); the nearest one's value when
/// they are equidistant, and 0 when none has a weight.
pub fn fill_weightless(x: &[[f64; 2]], p: &mut [f64], weightless: &[bool]) {
    for k in 0..x.len() {
        if !weightless[k] {
            continue;
        }
        let xk = x[k];
        let mut near: Vec<(f64, f64)> = (0..x.len())
            .filter(|&j| !weightless[j])
            .map(|j| {
                let y = x[j];
                ((xk[0] - y[0]).hypot(xk[1] - y[1]), p[j])
            })
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        p[k] = match near[..] {
            [] => 0.0,
            [(_, p1)] => p1,
            [(d1, p1), (d2, p2), ..] if d2 * d2 - d1 * d1 > 1e-12 * d2 * d2 => {
                (p1 * d2 * d2 - p2 * d1 * d1) / (d2 * d2 - d1 * d1)
            }
            [(_, p1), ..] => p1,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate::rectangle;
    use crate::mesh::CellKind;

    #[test]
    fn an_even_profile_is_recovered_exactly_on_the_axis() {
        let m = rectangle([0.0, 0.0], 2.0, 1.0, 4, 1, CellKind::Quad4, 0.0).unwrap();
        let nodes = m.node_group("Bottom").unwrap(); // x = 0, 0.5, ..., 2 on y = 0
        let x: Vec<[f64; 2]> = nodes.iter().map(|&n| m.coords[n]).collect();
        let profile = |r: f64| 7.0 - 3.0 * r * r;
        let mut p: Vec<f64> = nodes.iter().map(|&n| profile(m.coords[n][0])).collect();
        let weightless: Vec<bool> = nodes.iter().map(|&n| m.coords[n][0] == 0.0).collect();
        let axis = weightless.iter().position(|&w| w).unwrap();
        p[axis] = f64::INFINITY;
        fill_weightless(&x, &mut p, &weightless);
        assert!((p[axis] - 7.0).abs() < 1e-12, "{}", p[axis]);
    }
}
